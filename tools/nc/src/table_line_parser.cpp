// SPDX-License-Identifier: MIT
#include "table_line_parser.h"

#include <fmt/format.h>

#include <utility>

namespace apci::nc {

bool TableLineParser::fail(ErrorKind kind, std::uint32_t column, std::string message) {
    err_->kind = kind;
    err_->file = std::string(file_);
    err_->line = line_;
    err_->column = column;
    err_->block = kNoBlockNumber;
    err_->message = std::move(message);
    return false;
}

bool TableLineParser::field_number(LineCursor& c, const std::string& label, double& value,
                                   std::uint32_t& column) {
    const std::size_t before = c.offset();
    c.skip_blanks();
    column = c.column();
    if (c.offset() == before && !c.at_end())
        return fail(ErrorKind::kSyntax, column,
                    fmt::format("expected a blank and the value after '{}'", label));
    switch (c.scan_number(value)) {
        case NumberScan::kNone:
            return fail(ErrorKind::kSyntax, column,
                        fmt::format("expected a value after '{}'", label));
        case NumberScan::kOutOfRange:
            return fail(ErrorKind::kValue, column,
                        fmt::format("the value of {} is out of range", label));
        case NumberScan::kOk:
            break;
    }
    return true;
}

}  // namespace apci::nc
