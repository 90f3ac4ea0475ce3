// SPDX-License-Identifier: MIT
// Objects by name in apcictl: the dotted names of the object map (objif/names.h,
// docs/object-map.md section 8) as `read`, `write`, `dump` and `diff` take and show them.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "objif/names.h"

namespace apcictl {

// A word that names an object by name rather than by BUS: it starts with a letter
// ("tc.group[1].radius"); a number never does ("1300", "-1", "0x514").
bool is_object_name(std::string_view word) noexcept;

// The object `name` names, or nullptr with `error` set to
// "unknown object 'tc.group[1].radus'; did you mean 'tc.group[1].radius'?" (up to 3 names).
const objif::NamedObject* resolve_object_name(std::string_view name, std::string& error);

// "1300/1/1/7".
std::string address_text(const objif::Address& a);
// "tc.group[1].radius (1300/1/1/7)"; "1300/1/9/3" for an address the map does not name.
std::string object_label(const objif::Address& a);

// Whether `name` is under `prefix` by whole components: `tc` holds tc.init.tc_plane,
// `tc.group` and `tc.group[1]` hold tc.group[1].radius, and a name holds itself; `tc.gr`
// holds nothing. The empty prefix holds every name.
bool name_has_prefix(std::string_view name, std::string_view prefix) noexcept;

// Up to `max` prefixes (whole components of the map's names, as name_has_prefix takes them)
// closest to `typed` (edit distance at most a third of the longer), closest first.
std::vector<std::string> nearest_prefixes(std::string_view typed, std::size_t max = 3);

// "'a'", "'a' or 'b'", "'a', 'b' or 'c'".
std::string quoted_choices(const std::vector<std::string>& names);

}  // namespace apcictl
