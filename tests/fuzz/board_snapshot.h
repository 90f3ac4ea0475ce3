// SPDX-License-Identifier: MIT
// What a client can observe of a Board: the status and value of every
// readable object at every index of its table row. Two equal snapshots mean
// no observable state changed in between.
#pragma once

#include <cstdint>
#include <vector>

#include "objif/dictionary.h"
#include "rwmos/board.h"

namespace fuzz {

struct ObservedObject {
    objif::Address address;
    objif::Status status = objif::Status::kOk;
    objif::Value value;

    friend bool operator==(const ObservedObject& a, const ObservedObject& b) noexcept {
        // Doubles are compared bit for bit through Value's ==; every value is finite.
        return a.address == b.address && a.status == b.status && a.value == b.value;
    }
};

inline std::vector<ObservedObject> snapshot(rwmos::Board& board) {
    std::vector<ObservedObject> seen;
    for (objif::Module* module : board.dictionary().modules()) {
        for (std::size_t i = 0; i < module->object_count(); ++i) {
            const objif::ObjectInfo& info = module->object_at(i);
            if (!objif::can_read(info.access)) continue;
            for (std::int32_t index = info.index_first; index <= info.index_last; ++index) {
                ObservedObject o;
                o.address = {module->bus(), info.device, index, info.subindex};
                objif::Descriptor d{o.address, objif::kNoHandle};
                o.status = board.read(d, info.type, o.value);
                seen.push_back(o);
            }
        }
    }
    return seen;
}

}  // namespace fuzz
