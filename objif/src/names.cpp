// SPDX-License-Identifier: MIT
// Dotted names of the object map (objif/names.h).
#include "objif/names.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <optional>
#include <unordered_map>
#include <utility>

namespace objif {
namespace {

std::string_view device_key(const map::ModuleMap& m, std::int32_t device) {
    for (const map::DeviceMap& d : m.devices)
        if (d.device == device) return d.key;
    return {};
}

// A row of the map as one suggestion candidate: its name with "[]" for a range of indices
// ("comp3d.tool[].r"), so a suggestion compares the typed text with some 140 rows, not with
// every one of the 8,376 addresses.
struct Shape {
    std::string text;
    const ObjectInfo* info;
    std::size_t first;  // the row's first object in Index::objects
};

struct Index {
    std::vector<NamedObject> objects;
    std::vector<Shape> shapes;
    std::unordered_map<std::string_view, std::size_t> by_name;
    std::unordered_map<Address, std::size_t, AddressHash> by_address;
};

Index build() {
    Index ix;
    for (const map::ModuleMap& m : map::kModules) {
        for (const ObjectInfo& o : m.objects) {
            if (o.key.empty()) continue;
            // MODULE[.DEVICE], then [INDEX] for a range of indices, then .KEY.
            const std::string_view dev = device_key(m, o.device);
            const std::string prefix =
                dev.empty() ? std::string(m.key) : fmt::format("{}.{}", m.key, dev);
            const bool ranged = o.index_first != o.index_last;
            ix.shapes.push_back(
                {fmt::format("{}{}.{}", prefix, ranged ? "[]" : "", o.key), &o, ix.objects.size()});
            for (std::int32_t i = o.index_first; i <= o.index_last; ++i) {
                std::string name = ranged ? fmt::format("{}[{}].{}", prefix, i, o.key)
                                          : fmt::format("{}.{}", prefix, o.key);
                ix.objects.push_back({std::move(name), {m.bus, o.device, i, o.subindex}, &o, &m});
            }
        }
    }
    // The maps refer to the names' characters: filled once the vector no longer moves.
    for (std::size_t k = 0; k < ix.objects.size(); ++k) {
        ix.by_name.emplace(ix.objects[k].name, k);
        ix.by_address.emplace(ix.objects[k].address, k);
    }
    return ix;
}

const Index& index() {
    static const Index ix = build();
    return ix;
}

char lower(char c) noexcept {
    return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
}

// The Damerau-Levenshtein distance (optimal string alignment) of a and b ignoring ASCII case,
// or bound + 1 as soon as it is known to exceed `bound`: from the lengths alone, or once a row
// of the table has every entry above it (the least entry of a row never falls from one row to
// the next: every step of the recurrence adds to an entry of the row before, and the swap's
// two-rows-back entry plus 1 is at least the substitution's entry of the row before). Three
// rows of the table, on the stack for names of up to kRow - 1 characters: a suggestion
// compares the typed text with each of the map's 8,376 names.
std::size_t bounded_edit_distance(std::string_view a, std::string_view b, std::size_t bound) {
    const std::size_t gap = a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
    if (gap > bound) return bound + 1;
    constexpr std::size_t kRow = 96;
    std::array<std::size_t, kRow> r0{}, r1{}, r2{};
    std::vector<std::size_t> heap;
    std::size_t* two_back = r0.data();
    std::size_t* back = r1.data();
    std::size_t* row = r2.data();
    if (b.size() + 1 > kRow) {
        heap.resize(3 * (b.size() + 1));
        two_back = heap.data();
        back = two_back + b.size() + 1;
        row = back + b.size() + 1;
    }
    for (std::size_t j = 0; j <= b.size(); ++j) back[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        row[0] = i;
        std::size_t row_min = row[0];
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            row[j] = std::min({back[j] + 1, row[j - 1] + 1, back[j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
                row[j] = std::min(row[j], two_back[j - 2] + 1);
            row_min = std::min(row_min, row[j]);
        }
        if (row_min > bound) return bound + 1;
        std::swap(two_back, back);  // two_back: row i - 1
        std::swap(back, row);       // back: row i; row: the storage of row i - 2, reused
    }
    return back[b.size()];
}

}  // namespace

std::span<const NamedObject> named_objects() {
    return index().objects;
}

const NamedObject* find_object(std::string_view name) noexcept {
    const Index& ix = index();
    const auto it = ix.by_name.find(name);
    return it == ix.by_name.end() ? nullptr : &ix.objects[it->second];
}

const NamedObject* find_object(const Address& a) noexcept {
    const Index& ix = index();
    const auto it = ix.by_address.find(a);
    return it == ix.by_address.end() ? nullptr : &ix.objects[it->second];
}

namespace {

// The names within reach of `typed` with their edit distances, nearest first (ties in map
// order).
std::vector<std::pair<std::size_t, std::string_view>> matches(std::string_view typed) {
    // The typed text with its first bracketed number taken out ("tc.group[7].radus" ->
    // "tc.group[].radus", index 7), to meet the rows over a range of indices.
    std::string typed_shape(typed);
    std::optional<std::int64_t> typed_index;
    if (const auto open = typed.find('['); open != std::string_view::npos) {
        const auto close = typed.find(']', open);
        const std::string_view digits = close == std::string_view::npos
                                            ? std::string_view{}
                                            : typed.substr(open + 1, close - open - 1);
        if (!digits.empty() && digits.size() <= 9 &&
            std::all_of(digits.begin(), digits.end(),
                        [](char c) { return c >= '0' && c <= '9'; })) {
            typed_index = std::stoll(std::string(digits));
            typed_shape = std::string(typed.substr(0, open + 1)) + std::string(typed.substr(close));
        }
    }
    const Index& ix = index();
    std::vector<std::pair<std::size_t, std::string_view>> close;
    for (const Shape& shape : ix.shapes) {
        const ObjectInfo& o = *shape.info;
        const bool ranged = o.index_first != o.index_last;
        const std::string_view compared = ranged ? std::string_view(typed_shape) : typed;
        const std::size_t bound = std::max(compared.size(), shape.text.size()) / 3;
        const std::size_t d = bounded_edit_distance(compared, shape.text, bound);
        if (d > bound) continue;
        // A row over a range is offered at the typed index, brought into the range.
        std::int64_t i = o.index_first;
        if (ranged && typed_index)
            i = std::clamp<std::int64_t>(*typed_index, o.index_first, o.index_last);
        close.emplace_back(
            d, ix.objects[shape.first + static_cast<std::size_t>(i - o.index_first)].name);
    }
    std::stable_sort(close.begin(), close.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    return close;
}

}  // namespace

std::vector<std::string_view> nearest_names(std::string_view typed, std::size_t max) {
    std::vector<std::string_view> out;
    for (const auto& [distance, name] : matches(typed)) {
        if (out.size() == max) break;
        out.push_back(name);
    }
    return out;
}

std::vector<std::string_view> closest_names(std::string_view typed, std::size_t max) {
    const auto close = matches(typed);
    std::vector<std::string_view> out;
    for (const auto& [distance, name] : close) {
        if (out.size() == max || distance != close.front().first) break;
        out.push_back(name);
    }
    return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
    return bounded_edit_distance(a, b, std::max(a.size(), b.size()));
}

}  // namespace objif
