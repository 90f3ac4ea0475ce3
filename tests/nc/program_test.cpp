// SPDX-License-Identifier: MIT
#include "apci/nc/program.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "apci/nc/tools.h"
#include "nc_test_util.h"
#include "text.h"

namespace apci::nc {
namespace {

using test_support::read_text;
using test::error_of;
using test::events_of;
using test::only;
using V = Eigen::Vector3d;

const std::string kExamples = APCI_EXAMPLES_DIR;

std::string temp_file(const std::string& name, const std::string& text) {
    std::string path = ::testing::TempDir() + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::vector<Event> execute(const Program& p) {
    Result<EventStream> s = p.events();
    EXPECT_TRUE(s) << s.error().to_string();
    std::vector<Event> out;
    if (!s) return out;
    Event ev;
    while (s.value().next(ev) == EventStream::Next::kEvent) out.push_back(ev);
    return out;
}

TEST(Program, ProgramNameIsReported) {
    Result<Program> p = Program::from_text("; header\n%demo.nc\nG0 X1\nM30\n", "demo");
    ASSERT_TRUE(p) << p.error().to_string();
    EXPECT_EQ(p.value().summary().name, "demo.nc");
}

TEST(Program, ProgramNameOnlyOnFirstSignificantLine) {
    EXPECT_EQ(error_of("G0 X1\n%late\nM30"),
              "prog.nc:2:1: '%name' must be the first line of the program (and appear once)");
    EXPECT_EQ(error_of("%a\n%b\nM30"),
              "prog.nc:2:1: '%name' must be the first line of the program (and appear once)");
}

// '%' alone: the tape's start mark on the first significant line, its end mark after the
// program's end; once each, nowhere else (post-processors write both).
TEST(Program, PercentAloneMarksTheTapesStartAndEnd) {
    EXPECT_EQ(error_of("%\nG0 X1\nM30\n%\n"), "");
    EXPECT_EQ(error_of("; header\n%\n%demo\nG0 X1\nM30\n\n% (end)\n; done\n"), "");
    EXPECT_EQ(error_of("G0 X1\nM2\n%\n"), "");
    const std::string rule =
        ": '%' alone marks the tape's start (the first line) or its end (after M30 or M2), "
        "once each";
    EXPECT_EQ(error_of("G0 X1\n%\nM30\n"), "prog.nc:2:1" + rule);
    EXPECT_EQ(error_of("%\n  %\nG0 X1\nM30\n"), "prog.nc:2:3" + rule);
    EXPECT_EQ(error_of("%demo\n%\nG0 X1\nM30\n"), "prog.nc:2:1" + rule);
    EXPECT_EQ(error_of("G0 X1\nM30\n%\n%\n"), "prog.nc:4:1" + rule);
    EXPECT_EQ(error_of("G0 X1\nM30\n%\nG0 X2\n"),
              "prog.nc:4:1: block after M30: the program has already ended");
    EXPECT_EQ(error_of("%\nG0 X1\n%\n"), "prog.nc:3:1" + rule);
    EXPECT_EQ(error_of("%\nG0 X1\n"), "prog.nc:2:1: the program ends without M30");
}

// M2 ends a program as M30 does; nothing but comments after it.
TEST(Program, M2EndsTheProgram) {
    EXPECT_EQ(error_of("G0 X1\nM2\n; end\n"), "");
    EXPECT_EQ(error_of("G0 X1\nM02\nG0 X2\n"),
              "prog.nc:3:1: block after M30: the program has already ended");
}

// A UTF-8 byte-order mark at the start of the program is left out (and not counted in the first
// line's length); anywhere else it is an unexpected character.
TEST(Program, AByteOrderMarkAtTheStartIsLeftOut) {
    const std::string bom = "\xEF\xBB\xBF";
    EXPECT_EQ(error_of(bom + "G0 X1\nM30\n"), "");
    EXPECT_EQ(error_of(bom + "%\nG0 X1\nM30\n%\n"), "");
    EXPECT_EQ(error_of(bom + "%demo\nG0 X1\nM30\n"), "");
    EXPECT_EQ(error_of(bom + "G0 X1 @\nM30\n").rfind("prog.nc:1:7: unexpected character '@'", 0),
              0u)
        << "columns count from after the mark";
    EXPECT_NE(error_of("G0 X1\n" + bom + "M30\n"), "");
    EXPECT_NE(error_of(" " + bom + "G0 X1\nM30\n"), "");
    // The first line at the length bound after the mark, in text and through a file's buffer.
    for (std::size_t length : {LineSource::kMaxLineLength, LineSource::kMaxLineLength + 1}) {
        std::string text = bom + "G0 X1 ;";
        text.append(length - 7, 'x');
        text += "\nM30\n";
        const bool fits = length == LineSource::kMaxLineLength;
        EXPECT_EQ(error_of(text), fits ? "" : "prog.nc:1:65537: line longer than 65536 characters");
        Result<Program> p = Program::load(temp_file("bom_edge.nc", text));
        EXPECT_EQ(static_cast<bool>(p), fits) << length;
    }
    // The tool list is read the same way.
    Result<ToolTable> tools = parse_tool_table(bom + "wz[1].radius 5\n", "t.tools");
    EXPECT_TRUE(tools) << tools.error().to_string();
}

// Only the file's start: a mark at the start of a later line is an unexpected character, also
// where that line is the first of a file's buffer when it is read again (at 2 * 65,536 bytes).
TEST(Program, AByteOrderMarkAtTheStartOfALaterBufferIsNoMark) {
    const std::string bom = "\xEF\xBB\xBF";
    const std::size_t buffer = 2 * LineSource::kMaxLineLength;
    for (std::size_t before : {std::size_t{0}, std::size_t{2}}) {  // starts at, straddles it
        std::string text;
        std::size_t lines = 0;
        while (text.size() + 1000 <= buffer - before) {
            text += "; " + std::string(997, 'x') + "\n";
            ++lines;
        }
        text += "; " + std::string(buffer - before - text.size() - 3, 'x') + "\n";
        ++lines;
        ASSERT_EQ(text.size(), buffer - before);
        text += bom + "G0 X1\nM30\n";
        const std::string path = temp_file("bom_later_buffer.nc", text);
        Result<Program> p = Program::load(path);
        ASSERT_FALSE(p) << before;
        EXPECT_EQ(p.error().to_string().rfind(
                      path + ":" + std::to_string(lines + 1) + ":1: unexpected character", 0),
                  0u)
            << p.error().to_string();
    }
}

TEST(Program, KlartextDialectIsDetectedByBeginPgm) {
    // Told by content: these are Klartext programs (tests/nc/klartext_test.cpp), refused here
    // only because they stop before END PGM.
    EXPECT_EQ(error_of("0  BEGIN PGM 3DTEST MM\n1 TOOL CALL 1 Z\n"),
              "prog.nc:2:1: the program ends without END PGM");
    EXPECT_EQ(error_of("\n; header\nBEGIN PGM X MM\n"),
              "prog.nc:3:1: the program ends without END PGM");
    Result<EventStream> s =
        Program::from_text("BEGIN PGM X MM\nEND PGM X MM\n", "p").value().events();
    Event ev;
    ASSERT_EQ(s.value().next(ev), EventStream::Next::kEvent);
    EXPECT_EQ(s.value().dialect(), Dialect::kKlartext);
}

TEST(Program, WindowsLineEndsAndMissingFinalNewline) {
    const auto ev = events_of("G0 X1\r\nG0 X2\r\nM30");
    ASSERT_EQ(ev.size(), 3U);
    EXPECT_EQ(ev[2].origin.line, 3U);
}

TEST(Program, SummaryCountsLinesBlocksEventsMoves) {
    Result<Program> p = Program::from_text("%p\nN1 D1 G0 X1\n\nN2 G1 X2 F1\nN3 M30\n", "p");
    ASSERT_TRUE(p) << p.error().to_string();
    const ProgramSummary& s = p.value().summary();
    EXPECT_EQ(s.lines, 5U);
    EXPECT_EQ(s.blocks, 3U);
    EXPECT_EQ(s.events, 4U);  // tool, rapid, line, end
    EXPECT_EQ(s.moves, 2U);
}

// A stream on its own executes blocks until it meets the error; Program::load refuses the whole
// program first, so nothing of it is executed.
TEST(Program, NothingIsExecutedFromAProgramThatDoesNotParse) {
    const std::string text = "G0 X1\nG0 X2\nG0 X3\nG0 Q4\nM30\n";
    EventStream raw = EventStream::from_text(text, "bad.nc");
    Event ev;
    int executed = 0;
    while (raw.next(ev) == EventStream::Next::kEvent) ++executed;
    EXPECT_EQ(executed, 3);
    EXPECT_EQ(raw.error().to_string(),
              "bad.nc:4:4: unknown word 'Q' (known words: N G X Y Z B I J K R F D M, CDON CDOF)");
    EXPECT_EQ(raw.next(ev), EventStream::Next::kError);  // stays in error

    const std::string path = temp_file("bad.nc", text);
    Result<Program> p = Program::load(path);
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().to_string(),
              path + ":4:4: unknown word 'Q' (known words: N G X Y Z B I J K R F D M, CDON CDOF)");
}

TEST(Program, ExecutionPassRepeatsTheValidatedEvents) {
    const std::string path = temp_file("twice.nc", "G0 X1\nG1 Y2 F10\nG2 X3 Y4 R2\nM30\n");
    Result<Program> p = Program::load(path);
    ASSERT_TRUE(p) << p.error().to_string();
    const auto first = execute(p.value());
    const auto second = execute(p.value());
    ASSERT_EQ(first.size(), p.value().summary().events);
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
        EXPECT_EQ(first[i].data.index(), second[i].data.index());
        EXPECT_EQ(first[i].origin.line, second[i].origin.line);
    }
}

TEST(Program, FileChangedSinceValidationIsRefused) {
    const std::string path = temp_file("changing.nc", "G0 X1\nM30\n");
    Result<Program> p = Program::load(path);
    ASSERT_TRUE(p) << p.error().to_string();
    std::ofstream(path, std::ios::binary | std::ios::app) << "; appended\n";
    Result<EventStream> s = p.value().events();
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().kind, ErrorKind::kIo);
    EXPECT_EQ(s.error().to_string(),
              path + ": the file changed since it was validated; load it again");
}

TEST(Program, MissingFileIsIoError) {
    Result<Program> p = Program::load("/nonexistent/dir/prog.nc");
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().kind, ErrorKind::kIo);
    EXPECT_EQ(p.error().to_string(),
              "/nonexistent/dir/prog.nc: cannot open: No such file or directory");
}

TEST(Program, ReadErrorIsIoError) {
    // A directory opens but cannot be read.
    const std::string dir = ::testing::TempDir() + "nc_dir_as_program";
    std::filesystem::create_directories(dir);
    Result<Program> p = Program::load(dir);
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().kind, ErrorKind::kIo);
    EXPECT_EQ(p.error().to_string(), dir + ":1:1: read error: Is a directory");
}

TEST(Program, OverlongLineIsError) {
    std::string text = "G0 X1 ;";
    text.append(LineSource::kMaxLineLength, 'x');
    text += "\nM30\n";
    EXPECT_EQ(error_of(text), "prog.nc:1:65537: line longer than 65536 characters");
    const std::string path = temp_file("long.nc", text);
    Result<Program> p = Program::load(path);
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().to_string(), path + ":1:65537: line longer than 65536 characters");
}

// The bound at its edge: a line of exactly 65,536 characters (its line end, "\n" or "\r\n",
// not counted) is read, one more is refused naming the line and the column past the bound; in
// a file (read through the buffer) and in text alike.
TEST(Program, ALineOfExactlyTheLimitIsReadAndOneMoreIsRefused) {
    const auto line = [](std::size_t length) {
        std::string l = "G0 X1 ;";
        l.append(length - l.size(), 'x');
        return l;
    };
    for (const std::string end : {"\n", "\r\n"}) {
        const std::string good = line(LineSource::kMaxLineLength) + end + "M30" + end;
        EXPECT_EQ(error_of(good), "") << "text, line end " << end.size();
        const std::string good_path = temp_file("edge_ok.nc", good);
        Result<Program> ok = Program::load(good_path);
        EXPECT_TRUE(ok) << ok.error().to_string();
        const std::string bad =
            "G0 X2" + end + line(LineSource::kMaxLineLength + 1) + end + "M30" + end;
        EXPECT_EQ(error_of(bad), "prog.nc:2:65537: line longer than 65536 characters");
        const std::string bad_path = temp_file("edge_bad.nc", bad);
        Result<Program> refused = Program::load(bad_path);
        ASSERT_FALSE(refused);
        EXPECT_EQ(refused.error().to_string(),
                  bad_path + ":2:65537: line longer than 65536 characters");
    }
}

// The file reader's buffer holds two bounds' worth: a line of exactly the bound whose "\r" is
// the buffer's last byte, its "\n" not read yet, is still a line (it was refused as longer
// than the bound). The line before it fills the buffer's first half, less that one byte.
TEST(Program, ALineOfExactlyTheLimitWhoseLineEndStraddlesTheReadBufferIsRead) {
    const auto line = [](std::size_t length) {
        std::string l = "G0 X1 ;";
        l.append(length - l.size(), 'x');
        return l;
    };
    const std::string first = line(LineSource::kMaxLineLength - 2) + "\n";
    const std::string second = line(LineSource::kMaxLineLength) + "\r\n";
    ASSERT_EQ(first.size() + second.size() - 1, 2 * LineSource::kMaxLineLength);  // to the "\r"
    const std::string ok_path = temp_file("straddle_edge_ok.nc", first + second + "M30\r\n");
    Result<Program> ok = Program::load(ok_path);
    EXPECT_TRUE(ok) << ok.error().to_string();
    // One character more on the second line, whose "\r" then follows the buffer's end.
    const std::string bad_path = temp_file(
        "straddle_edge_bad.nc", first + line(LineSource::kMaxLineLength + 1) + "\r\nM30\r\n");
    Result<Program> refused = Program::load(bad_path);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().to_string(),
              bad_path + ":2:65537: line longer than 65536 characters");
}

TEST(Program, LinesAcrossTheReadBufferKeepTheirText) {
    // Enough lines of varying length that many straddle the file reader's buffer boundary.
    std::string text = "G1 F100\n";
    int n = 0;
    while (text.size() < std::size_t{3} * 2 * LineSource::kMaxLineLength) {
        ++n;
        // Appended piece by piece: gcc 12 at -O3 reports a false -Wrestrict on the chained
        // operator+ of a string literal and a temporary std::string.
        text += 'N';
        text += std::to_string(n);
        text += " X";
        text += std::to_string(n % 997);
        text += ".5 ( ";
        text.append(static_cast<std::size_t>(n % 13), 'c');
        text += ")\n";
    }
    text += "M30\n";
    const std::string path = temp_file("straddle.nc", text);
    Result<Program> p = Program::load(path);
    ASSERT_TRUE(p) << p.error().to_string();
    const auto lines = only<LineMove>(execute(p.value()));
    ASSERT_EQ(lines.size(), static_cast<std::size_t>(n));
    for (int i = 1; i <= n; ++i) {
        ASSERT_EQ(lines[static_cast<std::size_t>(i - 1)].end.x(), (i % 997) + 0.5) << i;
    }
}

// wr_quad_disc.nc of [ISG-OTC] section 2.2 without its #OTC lines.
TEST(Program, IsgOtcProgramWrQuadDiscParses) {
    Result<ToolTable> tools = load_tool_table(kExamples + "/tools/wr_quad_disc.tools");
    ASSERT_TRUE(tools) << tools.error().to_string();
    InterpreterOptions o;
    o.tools = &tools.value();
    Result<Program> p = Program::load(kExamples + "/wr_quad_disc.nc", o);
    ASSERT_TRUE(p) << p.error().to_string();
    EXPECT_EQ(p.value().summary().name, "wr_quad_disc.nc");
    const auto ev = execute(p.value());
    std::vector<std::string> names;
    std::vector<std::int64_t> blocks;
    for (const Event& e : ev) {
        names.emplace_back(event_name(e.data));
        blocks.push_back(e.origin.block);
    }
    // N22's G25 is the start state (no event); N80's G26 comes after N80's move.
    EXPECT_EQ(names, (std::vector<std::string>{"tool", "line", "compensation", "line", "line",
                                               "line", "corner", "line", "line", "compensation",
                                               "line", "end"}));
    EXPECT_EQ(blocks,
              (std::vector<std::int64_t>{22, 40, 55, 60, 70, 80, 80, 90, 95, 100, 100, 99999}));
    const auto lines = only<LineMove>(ev);
    ASSERT_EQ(lines.size(), 7U);
    EXPECT_EQ(lines[2].end, V(102, 0, 0));
    EXPECT_EQ(lines[3].end, V(102, 100, 0));
    EXPECT_EQ(lines[6].end, V(0, 0, 0));
    for (const LineMove& l : lines) EXPECT_EQ(l.feed, 600.0);
    EXPECT_EQ(std::get<CompensationChange>(ev[2].data).side, Compensation::kRight);
    EXPECT_EQ(std::get<CornerModeChange>(ev[6].data).mode, CornerMode::kCircular);
}

TEST(Program, IsgOtcGeneralExampleParses) {
    Result<Program> p = Program::load(kExamples + "/otc_general.nc");
    ASSERT_TRUE(p) << p.error().to_string();
    const auto ev = execute(p.value());
    const auto lines = only<LineMove>(ev);
    ASSERT_EQ(lines.size(), 3U);
    EXPECT_EQ(lines[0].feed, 10000.0);
    EXPECT_EQ(lines[1].end, V(1000, 0, 0));
}

TEST(Program, IsgOtcProgramWithOtcLinesGivesTheOtcEventInItsPlace) {
    std::string text = read_text(kExamples + "/wr_quad_disc.nc");
    const std::size_t at = text.find("N55");
    ASSERT_NE(at, std::string::npos);
    text.insert(at, "N50 #OTC ON[RADIUS DISC]\n");
    Result<Program> p = Program::from_text(text, "prog.nc");
    ASSERT_TRUE(p) << p.error().to_string();
    const auto ev = execute(p.value());
    bool found = false;
    for (const Event& e : ev) {
        if (const auto* o = std::get_if<OtcChange>(&e.data)) {
            found = true;
            EXPECT_EQ(e.origin.block, 50);
            EXPECT_EQ(o->command.on, true);
            EXPECT_EQ(o->command.type, OtcType::kRadius);
            EXPECT_EQ(o->command.mode, OtcMode::kDisc);
        }
    }
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace apci::nc
