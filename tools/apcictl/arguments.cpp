// SPDX-License-Identifier: MIT
#include "arguments.h"

#include <cstdint>

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
