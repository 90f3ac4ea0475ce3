// SPDX-License-Identifier: MIT
// Compiled by tests/objif/CMakeLists.txt with -fsyntax-only, once per ATTACH_CASE: case 0 (a
// table that follows the map) must compile, each other case (a table out of step with the map)
// must not: objif::attach checks a module's hooks at compile time.
#include <array>

#include "objif/dictionary.h"

namespace {

struct Module {
    objif::Status get(const objif::ObjectInfo&, const objif::Address&, objif::Value&) {
        return objif::Status::kOk;
    }
    objif::Status set(const objif::ObjectInfo&, const objif::Address&, const objif::Value&) {
        return objif::Status::kOk;
    }
};

using M = Module;
using objif::Access;

constexpr std::array<objif::ObjectInfo, 3> kObjects{{
    {.device = 0,
     .index_first = 0,
     .index_last = 0,
     .subindex = 1,
     .name = "ReadOnly",
     .access = Access::kRead},
    {.device = 0,
     .index_first = 0,
     .index_last = 0,
     .subindex = 2,
     .name = "WriteOnly",
     .access = Access::kWrite},
    {.device = 0,
     .index_first = 0,
     .index_last = 0,
     .subindex = 3,
     .name = "Both",
     .access = Access::kReadWrite},
}};

#if ATTACH_CASE == 0  // follows the map
constexpr std::array<objif::Hooks<M>, 3> kHooks{{
    {"ReadOnly", &M::get, nullptr},
    {"WriteOnly", nullptr, &M::set},
    {"Both", &M::get, &M::set},
}};
#elif ATTACH_CASE == 1  // a row out of step with the map
constexpr std::array<objif::Hooks<M>, 3> kHooks{{
    {"WriteOnly", nullptr, &M::set},
    {"ReadOnly", &M::get, nullptr},
    {"Both", &M::get, &M::set},
}};
#elif ATTACH_CASE == 2  // a readable object without its read hook
constexpr std::array<objif::Hooks<M>, 3> kHooks{{
    {"ReadOnly", nullptr, nullptr},
    {"WriteOnly", nullptr, &M::set},
    {"Both", &M::get, &M::set},
}};
#elif ATTACH_CASE == 3  // a read hook on an object that cannot be read
constexpr std::array<objif::Hooks<M>, 3> kHooks{{
    {"ReadOnly", &M::get, nullptr},
    {"WriteOnly", &M::get, &M::set},
    {"Both", &M::get, &M::set},
}};
#elif ATTACH_CASE == 4  // a write hook on a read-only object
constexpr std::array<objif::Hooks<M>, 3> kHooks{{
    {"ReadOnly", &M::get, &M::set},
    {"WriteOnly", nullptr, &M::set},
    {"Both", &M::get, &M::set},
}};
#elif ATTACH_CASE == 5  // a writable object without its write hook
constexpr std::array<objif::Hooks<M>, 3> kHooks{{
    {"ReadOnly", &M::get, nullptr},
    {"WriteOnly", nullptr, &M::set},
    {"Both", &M::get, nullptr},
}};
#endif

[[maybe_unused]] constexpr auto kTable = objif::attach(kObjects, kHooks);

}  // namespace
