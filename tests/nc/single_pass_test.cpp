// SPDX-License-Identifier: MIT
// nc::SinglePass (program.h): one pass that is the execution and the validation together gives
// what Program::load gives (the first error, or the summary), wherever the execution stopped.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <variant>

#include "apci/nc/program.h"

namespace apci::nc {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
    std::string path = ::testing::TempDir() + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// Pulls at most `limit` events (the executor stopping early); returns how many it got.
std::size_t execute(EventStream& s, std::size_t limit) {
    Event ev;
    std::size_t n = 0;
    while (n < limit && s.next(ev) == EventStream::Next::kEvent) ++n;
    return n;
}

void expect_same_summary(const ProgramSummary& a, const ProgramSummary& b) {
    EXPECT_EQ(a.file, b.file);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.lines, b.lines);
    EXPECT_EQ(a.blocks, b.blocks);
    EXPECT_EQ(a.events, b.events);
    EXPECT_EQ(a.moves, b.moves);
}

const std::string kValid =
    "%demo\nN1 D1 G0 X1\n\n$FOR P1 = 1, 3, 1\nN2 G1 X[P1] F100\n$ENDFOR\nN3 G2 X3 Y2 R2\nN4 M30\n";

TEST(SinglePass, AValidProgramGivesTheSummaryOfProgramLoadWhereverTheExecutionStopped) {
    const std::string path = temp_file("single_valid.nc", kValid);
    Result<Program> loaded = Program::load(path);
    ASSERT_TRUE(loaded) << loaded.error().to_string();
    for (std::size_t stop : {0U, 1U, 4U, 1000U}) {
        Result<SinglePass> pass = SinglePass::open_file(path);
        ASSERT_TRUE(pass) << pass.error().to_string();
        EXPECT_EQ(pass.value().size(), kValid.size());
        execute(pass.value().events(), stop);
        Result<ProgramSummary> s = pass.value().finish();
        ASSERT_TRUE(s) << stop << ": " << s.error().to_string();
        expect_same_summary(s.value(), loaded.value().summary());
    }
}

TEST(SinglePass, AnInvalidProgramGivesTheErrorOfProgramLoadEvenAtItsLastLine) {
    for (const std::string& text :
         {std::string("G0 X1\nG0 X2\nG0 Q4\nM30\n"), std::string("G0 X1\nG1 X2 F10\nM30\nG0 X3\n"),
          std::string("G0 X1\nG0 X2\n")}) {
        const std::string path = temp_file("single_bad.nc", text);
        Result<Program> loaded = Program::load(path);
        ASSERT_FALSE(loaded) << text;
        for (std::size_t stop : {0U, 1U, 1000U}) {
            Result<SinglePass> pass = SinglePass::open_file(path);
            ASSERT_TRUE(pass);
            execute(pass.value().events(), stop);
            Result<ProgramSummary> s = pass.value().finish();
            ASSERT_FALSE(s) << text << " stopped after " << stop;
            EXPECT_EQ(s.error().to_string(), loaded.error().to_string());
            EXPECT_EQ(s.error().kind, loaded.error().kind);
        }
    }
    Result<SinglePass> text = SinglePass::from_text("G0 X1\nG0 Q4\nM30\n", "<stdin>");
    execute(text.value().events(), 1000);
    Result<ProgramSummary> s = text.value().finish();
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().to_string(),
              "<stdin>:2:4: unknown word 'Q' (known words: N G X Y Z B I J "
              "K R F D M, CDON CDOF)");
}

TEST(SinglePass, AFileThatCannotBeOpenedIsTheErrorOfProgramLoad) {
    Result<SinglePass> pass = SinglePass::open_file("/nonexistent/dir/prog.nc");
    Result<Program> loaded = Program::load("/nonexistent/dir/prog.nc");
    ASSERT_FALSE(pass);
    ASSERT_FALSE(loaded);
    EXPECT_EQ(pass.error().kind, ErrorKind::kIo);
    EXPECT_EQ(pass.error().to_string(), loaded.error().to_string());
}

// A board whose V.G.WZ_AKT.WEAR.Z is 10 (the front end's own view: 0).
struct Board : VariableSource {
    bool read(const VariableRef& v, double& out, std::string& why) override {
        if (v.variable == NcVariable::kWear && v.index == 2) {
            out = 10.0;
            return true;
        }
        why = "not on this board";
        return false;
    }
};

// The board's values can take the stream another way than the validation pass (which has the
// front end's values): the answer is still the validation's.
TEST(SinglePass, AProgramThatReadsTheBoardsVariablesIsValidatedAsProgramLoadDoes) {
    Board board;
    // Valid with the board's value (1/10), invalid with the front end's (1/0).
    const std::string divides = "P1 = V.G.WZ_AKT.WEAR.Z\nG0 X[1/P1]\nM30\n";
    const std::string path = temp_file("single_divides.nc", divides);
    Result<Program> loaded = Program::load(path);
    ASSERT_FALSE(loaded);
    Result<SinglePass> pass = SinglePass::open_file(path);
    ASSERT_TRUE(pass);
    pass.value().events().set_variable_source(&board);
    EXPECT_EQ(execute(pass.value().events(), 1000), 2U);  // the move and M30: it ran
    EXPECT_TRUE(pass.value().events().read_variable_source());
    Result<ProgramSummary> s = pass.value().finish();
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().to_string(), loaded.error().to_string());

    // Invalid with the board (it cannot read WEAR_RADIUS), valid with the front end's view.
    const std::string text = "P1 = V.G.WZ_AKT.WEAR_RADIUS\nG0 X1\nM30\n";
    SinglePass q = SinglePass::from_text(text, "prog.nc");
    q.events().set_variable_source(&board);
    EXPECT_EQ(execute(q.events(), 1000), 0U);
    EXPECT_EQ(q.events().error().to_string(),
              "prog.nc:1:6: V.G.WZ_AKT.WEAR_RADIUS cannot be read: not on this board");
    Result<ProgramSummary> t = q.finish();
    ASSERT_TRUE(t) << t.error().to_string();
    expect_same_summary(t.value(), Program::from_text(text, "prog.nc").value().summary());
}

// A source that lost its board (a run that stopped while the front end read ahead of it,
// apci::run::ReadAhead) withdraws: the stream reads with its own view, as if the source had
// been taken away before, and the pass is not marked as having read the board.
TEST(SinglePass, AWithdrawnSourceLeavesTheStreamItsOwnView) {
    struct Gone : VariableSource {
        int reads = 0;
        bool read(const VariableRef&, double& out, std::string& why) override {
            ++reads;
            out = 99.0;
            why = "the run stopped";
            return false;
        }
        bool withdrawn() const noexcept override { return true; }
    } gone;
    const std::string text = "P1 = V.G.WZ_AKT.WEAR.Z\nG0 X[P1 + 1]\nM30\n";
    SinglePass pass = SinglePass::from_text(text, "prog.nc");
    pass.events().set_variable_source(&gone);
    Event ev;
    ASSERT_EQ(pass.events().next(ev), EventStream::Next::kEvent);
    EXPECT_EQ(gone.reads, 1);
    ASSERT_TRUE(std::holds_alternative<RapidMove>(ev.data));
    EXPECT_EQ(std::get<RapidMove>(ev.data).end.x(), 1.0);  // the front end's WEAR.Z: 0
    EXPECT_FALSE(pass.events().read_variable_source());
    Result<ProgramSummary> s = pass.finish();
    ASSERT_TRUE(s) << s.error().to_string();
    expect_same_summary(s.value(), Program::from_text(text, "prog.nc").value().summary());
}

// A program from a pipe is read once: it runs in one pass (Program::load could not read it
// again for the execution).
TEST(SinglePass, AProgramFromAPipeIsReadOnce) {
    const std::string path = ::testing::TempDir() + "single_fifo.nc";
    ::unlink(path.c_str());
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    std::thread writer([&] {
        std::FILE* f = std::fopen(path.c_str(), "w");
        if (f == nullptr) return;
        std::fputs(kValid.c_str(), f);
        std::fclose(f);
    });
    Result<SinglePass> pass = SinglePass::open_file(path);
    ASSERT_TRUE(pass) << pass.error().to_string();
    EXPECT_EQ(pass.value().size(), 0U);  // not known for a pipe
    execute(pass.value().events(), 2);
    Result<ProgramSummary> s = pass.value().finish();
    writer.join();
    ::unlink(path.c_str());
    ASSERT_TRUE(s) << s.error().to_string();
    expect_same_summary(s.value(), Program::from_text(kValid, path).value().summary());
}

// A pipe cannot be read a second time: a program from one that reads the board's variables
// is refused by name rather than waited for.
TEST(SinglePass, AProgramFromAPipeThatReadsTheBoardsVariablesIsRefusedByName) {
    const std::string path = ::testing::TempDir() + "single_fifo_vars.nc";
    ::unlink(path.c_str());
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    std::thread writer([&] {
        std::FILE* f = std::fopen(path.c_str(), "w");
        if (f == nullptr) return;
        std::fputs("P1 = V.G.WZ_AKT.WEAR.Z\nG0 X[P1]\nM30\n", f);
        std::fclose(f);
    });
    Board board;
    Result<SinglePass> pass = SinglePass::open_file(path);
    ASSERT_TRUE(pass);
    pass.value().events().set_variable_source(&board);
    execute(pass.value().events(), 1000);
    Result<ProgramSummary> s = pass.value().finish();
    writer.join();
    ::unlink(path.c_str());
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().kind, ErrorKind::kIo);
    EXPECT_NE(s.error().message.find("not a regular file"), std::string::npos) << s.error().message;
}

TEST(SinglePass, AFileChangedWhileItRanIsRefusedWhenItMustBeReadAgain) {
    Board board;
    const std::string path =
        temp_file("single_changed.nc", "P1 = V.G.WZ_AKT.WEAR.Z\nG0 X[P1]\nM30\n");
    Result<SinglePass> pass = SinglePass::open_file(path);
    ASSERT_TRUE(pass);
    pass.value().events().set_variable_source(&board);
    execute(pass.value().events(), 1000);
    std::ofstream(path, std::ios::binary | std::ios::app) << "; appended\n";
    Result<ProgramSummary> s = pass.value().finish();
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().to_string(), path + ": the file changed while it ran; run it again");
}

}  // namespace
}  // namespace apci::nc
