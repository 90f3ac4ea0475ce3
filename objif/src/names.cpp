// SPDX-License-Identifier: MIT
// Dotted names of the object map (objif/names.h).
#include "objif/names.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
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

// The typed text read as a name with an index: the number taken out and "[]" in its place, to
// meet the rows over a range of indices ("comp3d.tool[].r").
struct IndexedShape {
    std::string text;
    std::int64_t index;
};

// Every such reading of `typed`: its first bracketed number ("tc.group[7].radus" ->
// "tc.group[].radus", 7), or, without one, each number written straight after a letter and
// before a dot, a bracket or the end, as one would type an index without its brackets
// ("tc.group2.radius" -> "tc.group[].radius", 2; "comp3d.tool5.r" reads both the 3 and the 5,
// and the row nearest to a reading decides). Numbers of up to 9 digits.
std::vector<IndexedShape> indexed_shapes(std::string_view typed) {
    const auto digits_at = [&](std::size_t from, std::size_t to) {
        if (to <= from || to - from > 9) return false;
        return std::all_of(typed.begin() + static_cast<std::ptrdiff_t>(from),
                           typed.begin() + static_cast<std::ptrdiff_t>(to),
                           [](char c) { return c >= '0' && c <= '9'; });
    };
    const auto reading = [&](std::size_t from, std::size_t to, std::string_view open,
                             std::string_view close) {
        return IndexedShape{std::string(typed.substr(0, from)) + std::string(open) +
                                std::string(close) + std::string(typed.substr(to)),
                            std::stoll(std::string(typed.substr(from, to - from)))};
    };
    std::vector<IndexedShape> out;
    if (const auto open = typed.find('['); open != std::string_view::npos) {
        const auto close = typed.find(']', open);
        if (close != std::string_view::npos && digits_at(open + 1, close))
            out.push_back(reading(open + 1, close, "", ""));
        return out;
    }
    const auto is_letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
    for (std::size_t i = 1; i < typed.size(); ++i) {
        if (!is_letter(typed[i - 1]) || typed[i] < '0' || typed[i] > '9') continue;
        std::size_t end = i;
        while (end < typed.size() && typed[end] >= '0' && typed[end] <= '9') ++end;
        if ((end == typed.size() || typed[end] == '.') && digits_at(i, end))
            out.push_back(reading(i, end, "[", "]"));
        i = end;
    }
    return out;
}

// The names within reach of `typed` with their edit distances, nearest first (ties in map
// order).
std::vector<std::pair<std::size_t, std::string_view>> matches(std::string_view typed) {
    const std::vector<IndexedShape> typed_shapes = indexed_shapes(typed);
    const Index& ix = index();
    std::vector<std::pair<std::size_t, std::string_view>> close;
    for (const Shape& shape : ix.shapes) {
        const ObjectInfo& o = *shape.info;
        const bool ranged = o.index_first != o.index_last;
        // A row over a range meets each reading of the typed text with an index taken out,
        // and the nearest one counts (with its index); any other row meets the text as typed.
        std::size_t d = std::numeric_limits<std::size_t>::max();
        std::optional<std::int64_t> typed_index;
        const auto meet = [&](std::string_view compared, std::optional<std::int64_t> index) {
            const std::size_t bound = std::max(compared.size(), shape.text.size()) / 3;
            const std::size_t e = bounded_edit_distance(compared, shape.text, bound);
            if (e <= bound && e < d) {
                d = e;
                typed_index = index;
            }
        };
        meet(typed, std::nullopt);
        if (ranged)
            for (const IndexedShape& t : typed_shapes) meet(t.text, t.index);
        if (d == std::numeric_limits<std::size_t>::max()) continue;
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
