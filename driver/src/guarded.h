// SPDX-License-Identifier: MIT
// The driver's entry points are noexcept and answer with a status: guarded(f) runs f (which
// returns an objif::Status) and turns what it throws into one, out of memory into kNoMemory
// and anything else into kGeneralError. The one place the driver maps an exception.
#pragma once

#include <new>

#include "objif/status.h"

namespace apci {

template <class F>
objif::Status guarded(F&& f) noexcept {
    try {
        return f();
    } catch (const std::bad_alloc&) {
        return objif::Status::kNoMemory;
    } catch (...) {
        return objif::Status::kGeneralError;
    }
}

}  // namespace apci
