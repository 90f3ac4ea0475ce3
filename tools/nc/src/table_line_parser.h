// SPDX-License-Identifier: MIT
// What the line parsers of the front end's table files (the tool table, tools.cpp; the
// correction table, correction_table.cpp) share: the diagnostic of the line in hand, and the
// number after a field's name.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "apci/nc/diagnostic.h"
#include "apci/nc/lexer.h"

namespace apci::nc {

class TableLineParser {
  protected:
    explicit TableLineParser(std::string_view file) : file_(file) {}

    // Line `n` is in hand; its failure is reported in `err`.
    void start_line(std::uint64_t n, Diagnostic& err) noexcept {
        line_ = n;
        err_ = &err;
    }
    std::uint64_t current_line() const noexcept { return line_; }

    // Reports a failure at `column` of the line in hand; false.
    bool fail(ErrorKind kind, std::uint32_t column, std::string message);

    // The number after the field `label` ("wz[1].r", "corr[2].dl"): one or more blanks (none at
    // the end of the line), then a number in range; `column` is where it starts.
    bool field_number(LineCursor& c, const std::string& label, double& value,
                      std::uint32_t& column);

  private:
    std::string_view file_;
    std::uint64_t line_ = 0;
    Diagnostic* err_ = nullptr;
};

}  // namespace apci::nc
