// SPDX-License-Identifier: MIT
// Numbers as typed on apcictl's command line and in scripts.
#pragma once

#include <cstdint>
#include <string_view>

namespace apcictl {

// "5", "-12", "+3", "0x1F", "-0x10": an int64, all characters used, no wrap-around.
bool parse_int64(std::string_view text, std::int64_t& out) noexcept;
// The same, in the int32 range.
bool parse_int32(std::string_view text, std::int32_t& out) noexcept;
// Any decimal floating-point form strtod knows ("2.5", "-1e-3", "7", "nan"),
// all characters used. Non-finite values parse; the board refuses them.
bool parse_double(std::string_view text, double& out) noexcept;

}  // namespace apcictl
