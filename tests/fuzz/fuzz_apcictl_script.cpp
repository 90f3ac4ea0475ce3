// SPDX-License-Identifier: MIT
// Fuzz target: the script reader of `apcictl script` (tools/apcictl/
// script_reader.h): one command a line, parsed with the same declarations as
// the command line. Nothing runs. Checked: no exception escapes; every
// non-blank, non-comment line is either a ready command or a usage error that
// says what was wrong; line numbers ascend and name lines of the input.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_check.h"
#include "script_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const auto lines = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    std::istringstream in(text);

    const apcictl::ParsedScript script = apcictl::parse_script(in);
    FUZZ_CHECK(!script.read_failed, "a string stream never fails to read");
    FUZZ_CHECK(script.too_large.empty(), "an input of the fuzzer's length is within the bounds");

    std::uint64_t last = 0;
    for (const auto& line : script.lines) {
        FUZZ_CHECK(line.number > last && line.number <= lines, "parsed lines ascend within the input");
        FUZZ_CHECK(line.command != nullptr, "a parsed line holds a command");
        last = line.number;
    }
    last = 0;
    for (const auto& error : script.errors) {
        FUZZ_CHECK(error.number > last && error.number <= lines, "bad lines ascend within the input");
        FUZZ_CHECK(error.outcome.exit == apcictl::Exit::kUsage, "a malformed line is a usage error");
        FUZZ_CHECK(!error.outcome.error.empty(), "a malformed line's error says what was wrong");
        last = error.number;
    }
    return 0;
}
