// SPDX-License-Identifier: MIT
// FUZZ_CHECK: an invariant of a fuzz target. A broken one prints what broke
// and aborts, which libFuzzer reports as a finding (and the replay test as a
// failure), so each check is a real test that can fail.
#pragma once

#include <cstdio>
#include <cstdlib>

#define FUZZ_CHECK(condition, what)                                                      \
    do {                                                                                 \
        if (!(condition)) {                                                              \
            std::fprintf(stderr, "%s:%d: invariant broken: %s (%s)\n", __FILE__, __LINE__, \
                         what, #condition);                                              \
            std::abort();                                                                \
        }                                                                                \
    } while (false)
