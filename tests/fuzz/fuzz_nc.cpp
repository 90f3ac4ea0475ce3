// SPDX-License-Identifier: MIT
// Fuzz target: the NC front end (tools/nc) on a whole program, both passes.
// The dialect is told by content (docs/design.md section 8), so one target covers
// every dialect: DIN 66025 programs and, once it lands, Klartext programs
// (add those to corpus/nc/ and their keywords to nc.dict).
//
// Checked: an error names a line of the input and says what was wrong; a
// program that validates streams exactly the events the validation counted,
// every coordinate is finite, every move starts where the last one ended,
// the events come in line order from lines of the input, the last one is M30,
// and the stream stays at its end once there.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <variant>

#include <Eigen/Core>

#include "apci/nc/program.h"
#include "fuzz_check.h"

namespace {

using namespace apci::nc;

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

struct MoveCheck {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // InterpreterOptions' default start
    std::uint64_t moves = 0;

    void operator()(const RapidMove& m) { move(m.start, m.end); }
    void operator()(const LineMove& m) {
        FUZZ_CHECK(std::isfinite(m.feed) && m.feed > 0, "a line's feed is finite and > 0");
        move(m.start, m.end);
    }
    void operator()(const ArcMove& m) {
        FUZZ_CHECK(std::isfinite(m.feed) && m.feed > 0, "an arc's feed is finite and > 0");
        FUZZ_CHECK(finite(m.center), "an arc's centre is finite");
        move(m.start, m.end);
    }
    template <class Other>
    void operator()(const Other&) {}

    void move(const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
        FUZZ_CHECK(finite(start) && finite(end), "a move's end points are finite");
        FUZZ_CHECK(start == position, "a move starts where the last one ended");
        position = end;
        ++moves;
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const auto lines = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n')) + 1;

    auto program = Program::from_text(text, "fuzz.nc");
    if (!program) {
        const Diagnostic& d = program.error();
        FUZZ_CHECK(!d.message.empty(), "an error says what was wrong");
        FUZZ_CHECK(d.file == "fuzz.nc", "an error names the file");
        FUZZ_CHECK(d.line >= 1 && d.line <= lines, "an error names a line of the program");
        return 0;
    }
    const ProgramSummary& summary = program.value().summary();
    auto stream = program.value().events();
    FUZZ_CHECK(stream.ok(), "a validated text program can be streamed");
    EventStream& events = stream.value();

    MoveCheck check;
    std::uint64_t count = 0;
    std::uint64_t last_line = 0;
    bool ended = false;
    Event event;
    EventStream::Next next;
    while ((next = events.next(event)) == EventStream::Next::kEvent) {
        FUZZ_CHECK(!ended, "nothing follows M30");
        FUZZ_CHECK(event.origin.line >= last_line && event.origin.line <= lines,
                   "events come in line order from lines of the program");
        last_line = event.origin.line;
        std::visit(check, event.data);
        ended = std::holds_alternative<ProgramEnd>(event.data);
        ++count;
    }
    FUZZ_CHECK(next == EventStream::Next::kEnd, "a validated program streams without error");
    FUZZ_CHECK(ended, "a program ends with M30");
    FUZZ_CHECK(count == summary.events, "both passes see the same events");
    FUZZ_CHECK(check.moves == summary.moves, "both passes see the same moves");
    FUZZ_CHECK(events.next(event) == EventStream::Next::kEnd, "the stream stays at its end");
    return 0;
}
