// SPDX-License-Identifier: MIT
#include "object_name.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <utility>

namespace apcictl {

bool is_object_name(std::string_view word) noexcept {
    if (word.empty()) return false;
    const char c = word.front();
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

std::string quoted_choices(const std::vector<std::string>& names) {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
        text += fmt::format("'{}'", names[i]);
    }
    return text;
}

const objif::NamedObject* resolve_object_name(std::string_view name, std::string& error) {
    if (const objif::NamedObject* o = objif::find_object(name)) return o;
    // The closest names only: tc.group[1].radus means tc.group[1].radius, not group 2's too.
    std::vector<std::string> meant;
    for (std::string_view n : objif::closest_names(name, 3)) meant.emplace_back(n);
    if (meant.empty())
        error = fmt::format(
            "unknown object '{}' (names: docs/object-map.md section 8, or 'apcictl dump')", name);
    else
        error = fmt::format("unknown object '{}'; did you mean {}?", name, quoted_choices(meant));
    return nullptr;
}

std::string address_text(const objif::Address& a) {
    return fmt::format("{}/{}/{}/{}", a.bus, a.device, a.index, a.subindex);
}

std::string object_label(const objif::Address& a) {
    const objif::NamedObject* o = objif::find_object(a);
    if (o == nullptr) return address_text(a);
    return fmt::format("{} ({})", o->name, address_text(a));
}

bool name_has_prefix(std::string_view name, std::string_view prefix) noexcept {
    if (prefix.empty()) return true;
    if (!name.starts_with(prefix)) return false;
    if (name.size() == prefix.size()) return true;
    const char next = name[prefix.size()];
    // "tc.group" is followed by "[1]"; "tc." (a trailing dot) ends its component itself.
    return next == '.' || next == '[' || prefix.back() == '.';
}

std::vector<std::string> nearest_prefixes(std::string_view typed, std::size_t max) {
    // Every whole-component prefix of every name, once.
    std::set<std::string_view> prefixes;
    for (const objif::NamedObject& o : objif::named_objects()) {
        const std::string_view name = o.name;
        for (std::size_t at = 0; at < name.size(); ++at)
            if (name[at] == '.' || name[at] == '[') prefixes.insert(name.substr(0, at));
        prefixes.insert(name);
    }
    std::vector<std::pair<std::size_t, std::string_view>> close;
    for (std::string_view p : prefixes) {
        const std::size_t bound = std::max(typed.size(), p.size()) / 3;
        const std::size_t gap =
            typed.size() > p.size() ? typed.size() - p.size() : p.size() - typed.size();
        if (gap > bound) continue;
        const std::size_t d = objif::edit_distance(typed, p);
        if (d <= bound) close.emplace_back(d, p);
    }
    // Closest first; among equals, the shorter (the module before its devices), then by name.
    std::sort(close.begin(), close.end(), [](const auto& a, const auto& b) {
        if (a.first != b.first) return a.first < b.first;
        if (a.second.size() != b.second.size()) return a.second.size() < b.second.size();
        return a.second < b.second;
    });
    std::vector<std::string> out;
    for (std::size_t k = 0; k < close.size() && out.size() < max; ++k)
        out.emplace_back(close[k].second);
    return out;
}

}  // namespace apcictl
