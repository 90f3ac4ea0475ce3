// SPDX-License-Identifier: MIT
#include "shell_complete.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <unordered_set>

namespace apcictl {
namespace {

bool is_blank(char c) {
    return std::isspace(static_cast<unsigned char>(c)) != 0;
}

// The words before the last one (the one being typed), and that last one.
struct SplitLine {
    std::vector<std::string_view> before;
    std::string_view partial;
};

SplitLine split(std::string_view line) {
    SplitLine split;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_blank(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !is_blank(line[i])) ++i;
        if (i > start) split.before.push_back(line.substr(start, i - start));
    }
    // A line that ends in its last word is still typing it; after a blank, a new one.
    if (!line.empty() && !is_blank(line.back()) && !split.before.empty()) {
        split.partial = split.before.back();
        split.before.pop_back();
    }
    return split;
}

void add_matches(std::span<const std::string> names, std::string_view partial,
                 std::vector<std::string>& out) {
    for (const auto& name : names) {
        if (!name.starts_with(partial)) continue;
        if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
    }
}

// The object names that start with `partial`, each cut after the first part it does not yet
// reach (after the next '.' or '['): "tc.", "tc.group[", "tc.group[1].", "tc.group[1].radius".
void add_name_parts(std::span<const std::string> names, std::string_view partial,
                    std::vector<std::string>& out) {
    std::unordered_set<std::string_view> seen;
    for (const auto& name : names) {
        if (!name.starts_with(partial)) continue;
        std::string_view part = name;
        const std::size_t cut = part.find_first_of(".[", partial.size());
        if (cut != std::string_view::npos) part = part.substr(0, cut + 1);
        if (seen.insert(part).second) out.emplace_back(part);
    }
}

// A name cut after a part ("tc.", "tc.group["): more of it is to come, so no blank after it.
bool is_name_part(std::string_view candidate) {
    return candidate.ends_with('.') || candidate.ends_with('[');
}

}  // namespace

std::vector<std::string> complete(std::string_view line_before_cursor,
                                  std::span<const std::string> commands,
                                  std::span<const std::string> objects) {
    std::vector<std::string> out;
    if (line_before_cursor.find('#') != std::string_view::npos) return out;
    const SplitLine line = split(line_before_cursor);
    if (line.before.empty()) {
        add_matches(commands, line.partial, out);
        return out;
    }
    const std::string_view command = line.before.front();
    if (command == "quit" || command == "exit") return out;
    if (command == "help" || command == "status") {
        if (line.before.size() != 1) return out;  // one argument at most
        if (command == "help") {
            add_matches(commands, line.partial, out);
        } else {
            static const std::array<std::string, 2> kSwitch{"on", "off"};
            add_matches(kSwitch, line.partial, out);
        }
        return out;
    }
    add_name_parts(objects, line.partial, out);
    return out;
}

std::string common_prefix(std::span<const std::string> candidates) {
    if (candidates.empty()) return {};
    std::string_view prefix = candidates.front();
    for (const auto& c : candidates.subspan(1)) {
        const auto mismatch = std::mismatch(prefix.begin(), prefix.end(), c.begin(), c.end());
        prefix = prefix.substr(0, static_cast<std::size_t>(mismatch.first - prefix.begin()));
    }
    return std::string(prefix);
}

TabAction tab_action(std::string_view line_before_cursor,
                     const std::vector<std::string>& candidates) {
    TabAction action;
    if (candidates.empty()) return action;
    const std::string_view partial = split(line_before_cursor).partial;
    if (candidates.size() == 1) {
        const std::string& only = candidates.front();
        action.insert = only.substr(std::min(partial.size(), only.size()));
        if (!is_name_part(only)) action.insert += ' ';
        return action;
    }
    const std::string prefix = common_prefix(candidates);
    if (prefix.size() > partial.size())
        action.insert = prefix.substr(partial.size());
    else
        action.listed = candidates;
    return action;
}

std::string candidate_columns(std::span<const std::string> candidates, std::size_t width,
                              std::size_t max_listed) {
    if (candidates.empty()) return {};
    if (candidates.size() > max_listed)
        return fmt::format("({} names; type more of the name)\n", candidates.size());
    std::size_t longest = 0;
    for (const auto& c : candidates) longest = std::max(longest, c.size());
    const std::size_t column = longest + 2;
    const std::size_t per_row = std::max<std::size_t>(1, width / column);
    std::string text;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const bool row_end = (i + 1) % per_row == 0 || i + 1 == candidates.size();
        if (row_end)
            text += candidates[i] + '\n';
        else
            text += fmt::format("{:<{}}", candidates[i], column);
    }
    return text;
}

}  // namespace apcictl
