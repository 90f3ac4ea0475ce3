// SPDX-License-Identifier: MIT
// Fuzz target: the emulator as a state machine. The input is a sequence of
// object reads and writes, spooled profiles, direct and SSF commands, clock
// steps and trace requests on one board; after every step the board's
// invariants are checked (emulator_harness.h lists them).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "emulator_harness.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::BoardPort port;
    fuzz::EmulatorHarness harness(port);
    fuzz::ByteSource bytes({data, size});
    const std::string broken = harness.run(bytes);
    FUZZ_CHECK(broken.empty(), broken.c_str());
    return 0;
}
