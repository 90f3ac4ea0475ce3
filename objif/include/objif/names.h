// SPDX-License-Identifier: MIT
// Objects by name: every address of the board's object map (objif/map/objects.h) gets a
// stable dotted name built from the map's tables, so a host can say tc.group[1].radius where
// the interface wants (1300, 1, 1, 7). The scheme (docs/object-map.md "Names"):
//
//     MODULE[.DEVICE][[INDEX]].KEY
//
//   MODULE  the module's key: board, tc, comp3d, tempcomp, otc;
//   DEVICE  the device's key (tc.init, tc.group, otc.tool, ...); none for a module of one
//           device (board.axis_count);
//   [INDEX] the Index, for a row of objects over a range of indices (tc.group[0..3],
//           comp3d.tool[0..1023], otc.axis[0..7]);
//   KEY     the object's key, lower case with underscores; a SubIndex that numbers axes or
//           components is part of it (board.position[3], tempcomp.offset[2]).
//
// Names are matched exactly (lower case); nearest_names() suggests what was meant.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "objif/descriptor.h"
#include "objif/map/objects.h"
#include "objif/object_info.h"

namespace objif {

struct NamedObject {
    std::string name;        // "tc.group[1].radius"
    Address address;         // (1300, 1, 1, 7)
    const ObjectInfo* info;  // the map's row: type, access, range, default, unit, rule
    const map::ModuleMap* module;
};

// Every address of the map, in map order (module by bus, then the rows as declared, each
// row's indices in order). Built once, on first use; thread-safe.
std::span<const NamedObject> named_objects();

// The object a dotted name names, or nullptr.
const NamedObject* find_object(std::string_view name) noexcept;
// The object at an address, or nullptr when the map has none there.
const NamedObject* find_object(const Address& a) noexcept;

// Up to `max` names closest to `typed` (edit distance, ties in map order), for "did you
// mean": only names within a distance of a third of the longer name's length.
std::vector<std::string_view> nearest_names(std::string_view typed, std::size_t max = 3);
// Of those, only the names as close as the closest (up to `max`), for an error message:
// tc.group[1].radus means tc.group[1].radius, not also group 2's radius one step further.
std::vector<std::string_view> closest_names(std::string_view typed, std::size_t max = 3);

// The Damerau-Levenshtein distance (optimal string alignment: insertions, deletions,
// substitutions and swaps of two neighbours, each 1), ignoring ASCII case.
std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace objif
