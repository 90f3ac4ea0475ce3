// SPDX-License-Identifier: MIT
#include "arguments.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "value_text.h"

namespace apcictl {
namespace {

// The mark before a protected negative number: a control character no one types.
constexpr std::string_view kMark = "\x1f";

bool reads_as_negative_number(std::string_view text) {
    if (text.size() < 2 || text[0] != '-' || text[1] == '-') return false;
    std::int32_t i = 0;
    double d = 0.0;
    return parse_int32(text, i) || parse_double(text, d);
}

}  // namespace

std::string parse_integer(std::string_view name, std::string_view text, std::int64_t min,
                          std::int64_t max, std::int64_t& out) {
    const auto refused = [&] {
        return fmt::format("{} '{}' is not a whole number in {}..{}", name, text, min, max);
    };
    std::int64_t value = 0;
    if (!parse_int64(text, value)) return refused();
    if (value < min || value > max) return refused();
    out = value;
    return {};
}

std::string parse_int32_argument(std::string_view name, std::string_view text, std::int32_t& out) {
    std::int64_t value = 0;
    std::string why = parse_integer(name, text, std::numeric_limits<std::int32_t>::min(),
                                    std::numeric_limits<std::int32_t>::max(), value);
    if (why.empty()) out = static_cast<std::int32_t>(value);
    return why;
}

std::string parse_non_negative(std::string_view name, std::string_view text, double& out) {
    double value = 0.0;
    if (!parse_double(text, value) || !std::isfinite(value) || value < 0.0 || std::signbit(value))
        return fmt::format("{} '{}' is not a finite number >= 0", name, text);
    out = value;
    return {};
}

void protect_negative_numbers(std::vector<std::string>& args) {
    for (auto& arg : args)
        if (reads_as_negative_number(arg)) arg.insert(0, kMark);
}

void accept_negative_numbers(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        option->transform([](std::string value) {
            if (value.starts_with(kMark) && reads_as_negative_number(value.substr(kMark.size())))
                value.erase(0, kMark.size());
            return value;
        });
    }
}

std::string plain_text(std::string text) {
    for (auto at = text.find(kMark); at != std::string::npos; at = text.find(kMark, at))
        text.erase(at, kMark.size());
    return text;
}

}  // namespace apcictl
