// SPDX-License-Identifier: MIT
// The context of one block's rule checks, shared by the DIN interpreter (interpreter.cpp) and the
// Klartext interpreter (klartext_interpreter.cpp): the block, its file and the diagnostic a
// broken rule fills.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "apci/nc/diagnostic.h"

namespace apci::nc {

template <class BlockType>
struct BlockContext {
    const BlockType& b;
    std::string_view file;
    Diagnostic& err;
    bool klartext = false;  // a Klartext block: its number is not printed (Diagnostic::klartext)

    // Reports the broken rule at `column` of the block's line (0: its start); false.
    bool fail(ErrorKind kind, std::uint32_t column, std::string message) const {
        err.kind = kind;
        err.file = std::string(file);
        err.line = b.line;
        err.column = column == 0 ? 1 : column;
        err.block = b.block_number();
        if (klartext) err.klartext = true;
        err.message = std::move(message);
        err.undefined = Undefined::kNothing;
        return false;
    }
};

}  // namespace apci::nc
