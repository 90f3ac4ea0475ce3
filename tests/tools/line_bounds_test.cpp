// SPDX-License-Identifier: MIT
// What apcictl reads line by line is bounded the same way everywhere: a line of exactly
// 65,536 characters (its line end, "\n" or "\r\n", not counted) is a line, one more is refused
// with its line number; a script, checked whole before it runs, at most 100,000 lines and
// 16 MiB; a PLC script at most 16 MiB (docs/hardening.md, "Resource limits").
#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "apci/nc/source.h"
#include "apci/run/plc_script.h"
#include "line_editor.h"
#include "process.h"
#include "script_reader.h"
#include "text.h"

namespace {

using test_support::contains;
using apcictl::PlainLine;
using Kind = apcictl::PlainLine::Kind;

constexpr std::size_t kMax = 65'536;
static_assert(apcictl::kMaxLineLength == kMax);
static_assert(apci::run::kMaxPlcLineLength == kMax);
static_assert(apci::nc::LineSource::kMaxLineLength == kMax);

// Line numbers count every line read, also in the shell, whose input has no end: 64 bits (an
// int overflowed past 2^31 lines, undefined behaviour). A script line's and a bad line's number
// are the reader's type.
static_assert(std::is_same_v<decltype(apcictl::ScriptLine::number), std::uint64_t>);
static_assert(std::is_same_v<decltype(apcictl::ScriptLineError::number), std::uint64_t>);

// A script line of exactly `length` characters that parses: a command, blanks, a comment.
std::string line_of(std::size_t length, const std::string& command = "status") {
    std::string line = command + " #";
    line.append(length - line.size(), 'x');
    return line;
}

std::vector<PlainLine> plain_lines(const std::string& text, std::size_t max) {
    std::istringstream in(text);
    std::vector<PlainLine> lines;
    for (PlainLine l = apcictl::read_plain_line(in, max); l.kind != Kind::kEnd;
         l = apcictl::read_plain_line(in, max))
        lines.push_back(l);
    return lines;
}

TEST(LineBounds, APlainLineOfExactlyTheBoundIsALineAndOneMoreIsTooLong) {
    for (const char* end : {"\n", "\r\n"}) {
        const std::string at = std::string(kMax, 'a');
        const std::string past = std::string(kMax + 1, 'b');
        const auto lines = plain_lines(at + end + past + end + at, kMax);
        ASSERT_EQ(lines.size(), 3u);
        EXPECT_EQ(lines[0].kind, Kind::kLine);
        EXPECT_EQ(lines[0].text, at);
        EXPECT_EQ(lines[1].kind, Kind::kTooLong);
        EXPECT_EQ(lines[1].text, std::string(kMax, 'b'));
        EXPECT_EQ(lines[2].kind, Kind::kLine);  // the last, without a line end
        EXPECT_EQ(lines[2].text, at);
    }
    // The same through a FILE (the shell on a pipe).
    std::string text = std::string(kMax, 'c') + "\r\n" + std::string(kMax + 1, 'd') + "\n";
    std::FILE* f = ::fmemopen(text.data(), text.size(), "r");
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(apcictl::read_plain_line(f, kMax).kind, Kind::kLine);
    EXPECT_EQ(apcictl::read_plain_line(f, kMax).kind, Kind::kTooLong);
    EXPECT_EQ(apcictl::read_plain_line(f, kMax).kind, Kind::kEnd);
    std::fclose(f);
}

TEST(LineBounds, ALineWithoutEndIsReadNoFurtherThanAsked) {
    std::istringstream in(std::string(1000, 'z'));
    const PlainLine l = apcictl::read_plain_line(in, 10, 100);
    EXPECT_EQ(l.kind, Kind::kTooLong);
    EXPECT_EQ(l.consumed, 100u);
    EXPECT_EQ(in.rdbuf()->in_avail(), 900);
}

TEST(ScriptBounds, AScriptLineOfExactly65536CharactersParsesAndOneMoreIsRefused) {
    for (const char* end : {"\n", "\r\n"}) {
        std::istringstream in(line_of(kMax) + end + line_of(kMax + 1) + end + line_of(kMax));
        const apcictl::ParsedScript s = apcictl::parse_script(in);
        EXPECT_TRUE(s.too_large.empty());
        ASSERT_EQ(s.lines.size(), 2u);
        EXPECT_EQ(s.lines[0].number, 1u);
        EXPECT_EQ(s.lines[1].number, 3u);
        ASSERT_EQ(s.errors.size(), 1u);
        EXPECT_EQ(s.errors[0].number, 2u);
        EXPECT_EQ(s.errors[0].outcome.error,
                  "longer than 65536 characters; not run (it starts 'status #xxxxxxxxxxxx')");
    }
}

TEST(ScriptBounds, AScriptOfAtMostTheBoundsParsesAndOneLineOrByteMoreIsRefusedWhole) {
    std::string lines;
    for (std::uint64_t i = 0; i < apcictl::kMaxScriptLines - 1; ++i) lines += "#\n";
    lines += "status\n";
    {
        std::istringstream in(lines);
        const auto s = apcictl::parse_script(in);
        EXPECT_TRUE(s.too_large.empty()) << s.too_large;
        ASSERT_EQ(s.lines.size(), 1u);
        EXPECT_EQ(s.lines[0].number, apcictl::kMaxScriptLines);
    }
    {
        std::istringstream in(lines + "status\n");
        const auto s = apcictl::parse_script(in);
        EXPECT_EQ(s.too_large,
                  "longer than 100000 lines at line 100001: a script is checked whole before it "
                  "runs, so it may hold at most 100000 lines and 16 MiB; split it, or pipe it "
                  "into 'apcictl shell', which runs each line as it reads it");
    }
    // 16 MiB exactly: 256 lines of 65,535 characters and a line end.
    std::string bytes;
    for (int i = 0; i < 256; ++i) bytes += line_of(kMax - 1) + "\n";
    ASSERT_EQ(bytes.size(), apcictl::kMaxScriptBytes);
    {
        std::istringstream in(bytes);
        const auto s = apcictl::parse_script(in);
        EXPECT_TRUE(s.too_large.empty()) << s.too_large;
        EXPECT_EQ(s.lines.size(), 256u);
    }
    {
        std::istringstream in(bytes + "s");
        const auto s = apcictl::parse_script(in);
        EXPECT_TRUE(s.too_large.starts_with("longer than 16 MiB at line 257")) << s.too_large;
    }
}

TEST(PlcBounds, APlcLineOfExactly65536CharactersParsesAndOneMoreIsRefused) {
    const auto line = [](std::size_t length) {
        std::string l = "cycle 0 tool_holder 1 #";
        l.append(length - l.size(), 'x');
        return l;
    };
    for (const char* end : {"\n", "\r\n"}) {
        auto ok = apci::run::parse_plc_script(line(kMax) + end + line(kMax), "p.plc");
        ASSERT_TRUE(ok) << ok.error().to_string();
        EXPECT_EQ(ok.value().cycle_writes().size(), 2u);
        auto bad = apci::run::parse_plc_script(line(kMax) + end + line(kMax + 1), "p.plc");
        ASSERT_FALSE(bad);
        EXPECT_EQ(bad.error().to_string(), "p.plc:2:65537: line longer than 65536 characters");
    }
}

// A PLC script's lines are read as an NC program's (apci::nc::LineSource): a byte-order mark at
// its start is left out, one on a later line is the line's error.
TEST(PlcBounds, AByteOrderMarkAtTheStartIsLeftOut) {
    auto ok = apci::run::parse_plc_script("\xEF\xBB\xBF" "cycle 0 tool_holder 1\n", "p.plc");
    ASSERT_TRUE(ok) << ok.error().to_string();
    EXPECT_EQ(ok.value().cycle_writes().size(), 1u);
    auto bad = apci::run::parse_plc_script(
        "cycle 0 tool_holder 1\n\xEF\xBB\xBF" "cycle 1 tool_holder 1\n", "p.plc");
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().line, 2u);
}

// A PLC script is read with a bound: /dev/zero is refused after 16 MiB (it was read to 1.2 GB,
// then std::bad_alloc), and a file of 16 MiB + 1 byte likewise; 16 MiB is read.
TEST(PlcBounds, APlcScriptLargerThan16MiBIsRefusedUnread) {
    auto zero = apci::run::load_plc_script("/dev/zero");
    ASSERT_FALSE(zero);
    EXPECT_EQ(zero.error().to_string(),
              "/dev/zero: larger than 16 MiB: a PLC script is read whole before the run (one "
              "write a line)");
    std::string templ = ::testing::TempDir() + "plc_bounds_XXXXXX";
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    const std::string path = templ + "/big.plc";
    std::string text;
    while (text.size() + 24 <= apci::run::kMaxPlcScriptBytes) text += "cycle 0 tool_holder 1 #\n";
    text.append(apci::run::kMaxPlcScriptBytes - text.size() - 1, '#');
    text += '\n';
    ASSERT_EQ(text.size(), apci::run::kMaxPlcScriptBytes);
    std::ofstream(path, std::ios::binary) << text;
    EXPECT_TRUE(apci::run::load_plc_script(path));
    std::ofstream(path, std::ios::binary | std::ios::app) << "#";
    auto big = apci::run::load_plc_script(path);
    ASSERT_FALSE(big);
    EXPECT_TRUE(contains(big.error().to_string(), "larger than 16 MiB")) << big.error().to_string();
    std::remove(path.c_str());
    ::rmdir(templ.c_str());
}

// As processes: `apcictl script /dev/zero` and `yes status | apcictl script -` are refused
// (exit 2) and run nothing, instead of growing without end; `apcictl run --plc /dev/zero`
// likewise; the shell reading a pipe runs a line of exactly 65,536 characters and refuses one
// more, naming its line.
TEST(ScriptBounds, EndlessInputIsRefusedAndNothingRuns) {
    auto r = test_support::run_process({APCICTL_PATH, "script", "/dev/zero"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "apcictl: script: '/dev/zero' is longer than 16 MiB at line 1"))
        << r.err;
    r = test_support::run_process({"/bin/sh", "-c", "yes status | \"$0\" script -", APCICTL_PATH});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "apcictl: script: '-' is longer than 100000 lines at line 100001"))
        << r.err;
    EXPECT_EQ(r.out, "") << "a line ran";
    r = test_support::run_process({APCICTL_PATH, "run", "--plc", "/dev/zero", "/dev/null"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "/dev/zero: larger than 16 MiB")) << r.err;
}

// `apcictl script FILE` (its own reader of the file, not the one above): a script whose lines
// are exactly 65,536 characters runs; one line one character longer is refused by its number
// and nothing runs.
TEST(ScriptBounds, AScriptFileOfLinesOfExactly65536CharactersRunsAndOneMoreIsRefused) {
    std::string templ = ::testing::TempDir() + "script_bounds_XXXXXX";
    ASSERT_NE(::mkdtemp(templ.data()), nullptr);
    const std::string path = templ + "/edge.apci";
    for (const char* end : {"\n", "\r\n"}) {
        std::ofstream(path, std::ios::binary)
            << line_of(kMax, "read 1000 0 3 0") + end + line_of(kMax, "read 1000 0 3 0") + end;
        auto r = test_support::run_process({APCICTL_PATH, "script", path});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(r.out, "8\n8\n");
        std::ofstream(path, std::ios::binary)
            << line_of(kMax, "read 1000 0 3 0") + end + line_of(kMax + 1, "read 1000 0 3 0") + end;
        r = test_support::run_process({APCICTL_PATH, "script", path});
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_EQ(r.out, "") << "a line ran";
        EXPECT_EQ(r.err,
                  "apcictl: line 2: longer than 65536 characters; not run (it starts 'read 1000 0 "
                  "3 0 #xxx')\n");
    }
    std::remove(path.c_str());
    ::rmdir(templ.c_str());
}

TEST(ShellBounds, AShellLineOfExactly65536CharactersRunsAndOneMoreIsRefused) {
    const std::string input = line_of(kMax, "read 1000 0 3 0") + "\n" +
                              line_of(kMax + 1, "read 1000 0 3 0") + "\r\n" +
                              line_of(kMax, "read 1000 0 3 0") + "\r\n";
    const auto r = test_support::run_process({APCICTL_PATH, "shell"}, input);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.out, "8\n8\n");
    EXPECT_EQ(r.err,
              "apcictl: line 2: longer than 65536 characters; not run (it starts 'read 1000 0 3 0 "
              "#xxx')\n");
}

}  // namespace
