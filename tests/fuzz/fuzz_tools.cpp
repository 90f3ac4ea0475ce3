// SPDX-License-Identifier: MIT
// Fuzz target: the tool list parser (apci/nc/tools.h, the "wz[i].field value"
// form of [ISG-OTC] section 2.6). Checked: an error names a line and column of
// the input and what was wrong; a table that parses holds tools 1..1023 in
// ascending order, each found by its index, with every field in its
// documented range and finite.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "apci/nc/tools.h"
#include "fuzz_check.h"

namespace {

using namespace apci::nc;

void check_tool(const ToolData& t) {
    FUZZ_CHECK(t.gueltig == 0 || t.gueltig == 1, "gueltig is 0..1");
    FUZZ_CHECK(t.typ >= 0 && t.typ <= 3, "typ is 0..3");
    FUZZ_CHECK(t.mass_einheit == 0 || t.mass_einheit == 1, "mass_einheit is 0..1");
    const double lengths[] = {t.laenge, t.radius, t.grinding_wear_const, t.grinding_max_infeed,
                              t.grinding_disc_tilt_angle, t.r2, t.dl, t.dr, t.dr2};
    for (double v : lengths) FUZZ_CHECK(std::isfinite(v), "every tool value is finite");
    for (double v : t.ax_ersatz) FUZZ_CHECK(std::isfinite(v), "every axis offset is finite");
    FUZZ_CHECK(t.radius >= 0 && t.r2 >= 0 && t.grinding_wear_const >= 0,
               "radius, r2 and grinding_wear_const are >= 0");
    FUZZ_CHECK(std::abs(t.grinding_disc_tilt_angle) <= 450000, "the disc tilt is within +-45 degrees");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const auto lines = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n')) + 1;

    auto table = parse_tool_table(text, "fuzz.tools");
    if (!table) {
        const Diagnostic& d = table.error();
        FUZZ_CHECK(!d.message.empty(), "an error says what was wrong");
        FUZZ_CHECK(d.file == "fuzz.tools", "an error names the file");
        FUZZ_CHECK(d.line >= 1 && d.line <= lines, "an error names a line of the file");
        FUZZ_CHECK(d.column >= 1, "an error names a column");
        return 0;
    }
    int last = 0;
    for (const ToolData& t : table.value().tools()) {
        FUZZ_CHECK(t.index > last && t.index <= kMaxToolNumber, "tools ascend within 1..1023");
        FUZZ_CHECK(table.value().find(t.index) == &t, "every tool is found by its index");
        check_tool(t);
        last = t.index;
    }
    FUZZ_CHECK(table.value().find(0) == nullptr, "there is no tool 0");
    return 0;
}
