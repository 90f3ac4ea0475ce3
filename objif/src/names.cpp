// SPDX-License-Identifier: MIT
// Dotted names of the object map (objif/names.h).
#include "objif/names.h"

#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>
#include <utility>

namespace objif {
namespace {

struct AddressHash {
    std::size_t operator()(const Address& a) const noexcept {
        std::size_t h = static_cast<std::uint32_t>(a.bus);
        h = h * 1000003u ^ static_cast<std::uint32_t>(a.device);
        h = h * 1000003u ^ static_cast<std::uint32_t>(a.index);
        h = h * 1000003u ^ static_cast<std::uint32_t>(a.subindex);
        return h;
    }
};

std::string_view device_key(const map::ModuleMap& m, std::int32_t device) {
    for (const map::DeviceMap& d : m.devices)
        if (d.device == device) return d.key;
    return {};
}

struct Index {
    std::vector<NamedObject> objects;
    std::unordered_map<std::string_view, std::size_t> by_name;
    std::unordered_map<Address, std::size_t, AddressHash> by_address;
};

Index build() {
    Index ix;
    for (const map::ModuleMap& m : map::kModules) {
        for (const ObjectInfo& o : m.objects) {
            if (o.key.empty()) continue;
            const std::string_view dev = device_key(m, o.device);
            for (std::int32_t i = o.index_first; i <= o.index_last; ++i) {
                std::string name(m.key);
                if (!dev.empty()) name += fmt::format(".{}", dev);
                if (o.index_first != o.index_last) name += fmt::format("[{}]", i);
                name += fmt::format(".{}", o.key);
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

std::vector<std::string_view> nearest_names(std::string_view typed, std::size_t max) {
    std::vector<std::pair<std::size_t, std::string_view>> close;
    for (const NamedObject& o : index().objects) {
        const std::size_t bound = std::max(typed.size(), o.name.size()) / 3;
        // The lengths alone bound the distance from below: most names are skipped unseen.
        const std::size_t gap = typed.size() > o.name.size() ? typed.size() - o.name.size()
                                                             : o.name.size() - typed.size();
        if (gap > bound) continue;
        const std::size_t d = edit_distance(typed, o.name);
        if (d <= bound) close.emplace_back(d, o.name);
    }
    std::stable_sort(close.begin(), close.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::string_view> out;
    for (std::size_t k = 0; k < close.size() && out.size() < max; ++k)
        out.push_back(close[k].second);
    return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
    // d[i][j]: the distance between the first i characters of a and the first j of b.
    const std::size_t width = b.size() + 1;
    std::vector<std::size_t> d((a.size() + 1) * width);
    const auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * width + j]; };
    for (std::size_t i = 0; i <= a.size(); ++i) at(i, 0) = i;
    for (std::size_t j = 0; j <= b.size(); ++j) at(0, j) = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
                at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
        }
    }
    return at(a.size(), b.size());
}

}  // namespace objif
