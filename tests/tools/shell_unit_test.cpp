// SPDX-License-Identifier: MIT
// apcictl shell's pure parts: the completer, what a TAB does, the candidate list, the history
// file (where it is, reading it, writing it safely) and the plain reader of piped lines.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "line_editor.h"
#include "shell_complete.h"
#include "shell_history.h"

namespace {

using apcictl::complete;
using Strings = std::vector<std::string>;

const Strings kCommands{"read", "write", "status", "spool", "direct",
                        "ssf",  "step",  "help",   "quit",  "exit"};
const Strings kObjects{"tc.group[1].radius", "tc.group[1].wkzindex", "tc.group[2].radius",
                       "tc.init.tc_plane", "board.axis_count"};

// ---- complete()

TEST(ShellComplete, FirstWordCompletesCommandNames) {
    EXPECT_EQ(complete("wri", kCommands, kObjects), Strings{"write"});
    EXPECT_EQ(complete("s", kCommands, kObjects), (Strings{"status", "spool", "ssf", "step"}));
    EXPECT_EQ(complete("st", kCommands, kObjects), (Strings{"status", "step"}));
    EXPECT_EQ(complete("  he", kCommands, kObjects), Strings{"help"});  // blanks before it
    EXPECT_EQ(complete("", kCommands, kObjects), kCommands);            // every command
    EXPECT_EQ(complete("xyz", kCommands, kObjects), Strings{});
    EXPECT_EQ(complete("Read", kCommands, kObjects), Strings{});        // names are lower case
    EXPECT_EQ(complete("read", kCommands, kObjects), Strings{"read"});  // whole: the blank next
}

TEST(ShellComplete, LaterWordsCompleteObjectNamesOnePartAtATime) {
    EXPECT_EQ(complete("read ", kCommands, kObjects), (Strings{"tc.", "board."}));
    EXPECT_EQ(complete("read t", kCommands, kObjects), Strings{"tc."});
    EXPECT_EQ(complete("read tc.", kCommands, kObjects), (Strings{"tc.group[", "tc.init."}));
    EXPECT_EQ(complete("read tc.g", kCommands, kObjects), Strings{"tc.group["});
    EXPECT_EQ(complete("read tc.group[", kCommands, kObjects),
              (Strings{"tc.group[1].", "tc.group[2]."}));
    EXPECT_EQ(complete("read tc.group[1].", kCommands, kObjects),
              (Strings{"tc.group[1].radius", "tc.group[1].wkzindex"}));
    EXPECT_EQ(complete("read tc.group[1].r", kCommands, kObjects), Strings{"tc.group[1].radius"});
    EXPECT_EQ(complete("write  --double b", kCommands, kObjects), Strings{"board."});
    EXPECT_EQ(complete("read board.axis_count", kCommands, kObjects), Strings{"board.axis_count"});
    EXPECT_EQ(complete("read x", kCommands, kObjects), Strings{});
    // Object names, never command names, after a command.
    EXPECT_EQ(complete("read wri", kCommands, kObjects), Strings{});
}

TEST(ShellComplete, ShellWordsTakeTheirOwnArguments) {
    EXPECT_EQ(complete("help wr", kCommands, kObjects), Strings{"write"});
    EXPECT_EQ(complete("help ", kCommands, kObjects), kCommands);
    EXPECT_EQ(complete("help read ", kCommands, kObjects), Strings{});  // one argument at most
    EXPECT_EQ(complete("status o", kCommands, kObjects), (Strings{"on", "off"}));
    EXPECT_EQ(complete("status of", kCommands, kObjects), Strings{"off"});
    EXPECT_EQ(complete("status on ", kCommands, kObjects), Strings{});
    EXPECT_EQ(complete("quit ", kCommands, kObjects), Strings{});
    EXPECT_EQ(complete("exit t", kCommands, kObjects), Strings{});
}

TEST(ShellComplete, NothingInsideAComment) {
    EXPECT_EQ(complete("# wri", kCommands, kObjects), Strings{});
    EXPECT_EQ(complete("read tc.init.tc_plane # tc.", kCommands, kObjects), Strings{});
}

TEST(ShellComplete, EachCandidateOnceInListOrder) {
    const Strings twice{"step", "status", "step"};
    EXPECT_EQ(complete("st", twice, {}), (Strings{"step", "status"}));
    EXPECT_EQ(complete("read t", kCommands, Strings{}), Strings{});  // no names: nothing
}

// ---- common_prefix() and tab_action()

TEST(ShellComplete, CommonPrefix) {
    EXPECT_EQ(apcictl::common_prefix(Strings{}), "");
    EXPECT_EQ(apcictl::common_prefix(Strings{"status"}), "status");
    EXPECT_EQ(apcictl::common_prefix(Strings{"status", "step"}), "st");
    EXPECT_EQ(apcictl::common_prefix(Strings{"tc.group[1].radius", "tc.group[2].radius"}),
              "tc.group[");
    EXPECT_EQ(apcictl::common_prefix(Strings{"ab", "abc"}), "ab");
    EXPECT_EQ(apcictl::common_prefix(Strings{"x", "y"}), "");
}

TEST(ShellComplete, TabInsertsTheOneCandidateWithABlank) {
    const auto action = apcictl::tab_action("wri", Strings{"write"});
    EXPECT_EQ(action.insert, "te ");
    EXPECT_TRUE(action.listed.empty());
    EXPECT_EQ(apcictl::tab_action("read ", Strings{"board.axis_count"}).insert,
              "board.axis_count ");
    EXPECT_EQ(apcictl::tab_action("read", Strings{"read"}).insert, " ");
    // A name's part: the name goes on, no blank.
    EXPECT_EQ(apcictl::tab_action("read t", Strings{"tc."}).insert, "c.");
    EXPECT_EQ(apcictl::tab_action("read tc.g", Strings{"tc.group["}).insert, "roup[");
}

TEST(ShellComplete, TabExtendsToTheCommonPrefixThenLists) {
    const Strings groups{"tc.group[1].radius", "tc.group[2].radius"};
    const auto extend = apcictl::tab_action("read tc.gr", groups);
    EXPECT_EQ(extend.insert, "oup[");
    EXPECT_TRUE(extend.listed.empty());
    const auto list = apcictl::tab_action("read tc.group[", groups);
    EXPECT_EQ(list.insert, "");
    EXPECT_EQ(list.listed, groups);
    const auto none = apcictl::tab_action("xyz", Strings{});
    EXPECT_EQ(none.insert, "");
    EXPECT_TRUE(none.listed.empty());
}

TEST(ShellComplete, CandidatesInColumnsOrCounted) {
    EXPECT_EQ(apcictl::candidate_columns(Strings{"status", "spool", "ssf", "step"}, 80),
              "status  spool   ssf     step\n");
    EXPECT_EQ(apcictl::candidate_columns(Strings{"status", "spool", "ssf", "step"}, 17),
              "status  spool\nssf     step\n");
    EXPECT_EQ(apcictl::candidate_columns(Strings{"status", "spool"}, 3), "status\nspool\n");
    EXPECT_EQ(apcictl::candidate_columns(Strings{}, 80), "");
    EXPECT_EQ(apcictl::candidate_columns(Strings{"a", "b", "c"}, 80, 2),
              "(3 names; type more of the name)\n");
}

// ---- the history file

class ShellHistory : public ::testing::Test {
  protected:
    void SetUp() override {
        char pattern[] = "/tmp/apcictl_history_test.XXXXXX";
        ASSERT_NE(::mkdtemp(pattern), nullptr);
        dir_ = pattern;
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string path(const std::string& name) const { return dir_ + "/" + name; }
    static std::string read(const std::string& file) {
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }
    static void write(const std::string& file, const std::string& text) {
        std::ofstream(file) << text;
    }

    std::string dir_;
};

TEST(ShellHistoryPath, FromTheEnvironmentInOrder) {
    using apcictl::history_path;
    EXPECT_EQ(history_path("/x/h", "/state", "/home/u"), "/x/h");
    EXPECT_EQ(history_path("", "/state", "/home/u"), "");  // set but empty: no file
    EXPECT_EQ(history_path(nullptr, "/state", "/home/u"), "/state/apci/apcictl_history");
    EXPECT_EQ(history_path(nullptr, "relative", "/home/u"),
              "/home/u/.local/state/apci/apcictl_history");  // XDG wants an absolute path
    EXPECT_EQ(history_path(nullptr, nullptr, "/home/u"),
              "/home/u/.local/state/apci/apcictl_history");
    EXPECT_EQ(history_path(nullptr, nullptr, nullptr), "");
    EXPECT_EQ(history_path(nullptr, "", ""), "");
}

TEST(ShellHistoryLines, RememberedBoundedWithoutBlanksOrRepeats) {
    Strings entries;
    EXPECT_TRUE(apcictl::remember_line(entries, "read 1300 1 1 7"));
    EXPECT_FALSE(apcictl::remember_line(entries, "read 1300 1 1 7"));  // the same again
    EXPECT_FALSE(apcictl::remember_line(entries, "   "));
    EXPECT_FALSE(apcictl::remember_line(entries, ""));
    EXPECT_FALSE(apcictl::remember_line(entries, std::string(apcictl::kHistoryLineLimit + 1, 'x')));
    EXPECT_TRUE(apcictl::remember_line(entries, "status"));
    EXPECT_EQ(entries, (Strings{"read 1300 1 1 7", "status"}));
    for (int i = 0; i < 10; ++i) apcictl::remember_line(entries, std::to_string(i), 3);
    EXPECT_EQ(entries, (Strings{"7", "8", "9"}));
}

TEST_F(ShellHistory, SavedThenLoaded) {
    const std::string file = path("state/apci/apcictl_history");  // directories created
    EXPECT_EQ(apcictl::save_history(file, Strings{"read 1300 1 1 7", "status"}), "");
    EXPECT_EQ(read(file), "read 1300 1 1 7\nstatus\n");
    struct stat st {};
    ASSERT_EQ(::stat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
    ASSERT_EQ(::stat(path("state/apci").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0700u);
    const auto load = apcictl::load_history(file);
    EXPECT_EQ(load.warning, "");
    EXPECT_TRUE(load.writable);
    EXPECT_EQ(load.entries, (Strings{"read 1300 1 1 7", "status"}));
    // No temporary file is left next to it.
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(path("state/apci")))
        ++files;
    EXPECT_EQ(files, 1u);
}

TEST_F(ShellHistory, AbsentFileIsAnEmptyHistory) {
    const auto load = apcictl::load_history(path("none"));
    EXPECT_EQ(load.warning, "");
    EXPECT_TRUE(load.writable);
    EXPECT_TRUE(load.entries.empty());
}

TEST_F(ShellHistory, KeepsTheLastThousandEntries) {
    Strings many;
    for (int i = 0; i < 1500; ++i) many.push_back("step " + std::to_string(i + 1));
    const std::string file = path("h");
    EXPECT_EQ(apcictl::save_history(file, many), "");
    const auto load = apcictl::load_history(file);
    ASSERT_EQ(load.entries.size(), apcictl::kHistoryEntries);
    EXPECT_EQ(load.entries.front(), "step 501");
    EXPECT_EQ(load.entries.back(), "step 1500");
    // A longer file (written by hand) is read to its last thousand lines.
    std::string text;
    for (int i = 0; i < 1200; ++i) text += "read 1 2 3 " + std::to_string(i) + "\n";
    write(file, text);
    const auto longer = apcictl::load_history(file);
    ASSERT_EQ(longer.entries.size(), apcictl::kHistoryEntries);
    EXPECT_EQ(longer.entries.front(), "read 1 2 3 200");
}

TEST_F(ShellHistory, ALinkIsNeitherReadNorWritten) {
    const std::string target = path("target");
    write(target, "precious\n");
    const std::string link = path("link");
    ASSERT_EQ(::symlink(target.c_str(), link.c_str()), 0);
    const auto load = apcictl::load_history(link);
    EXPECT_FALSE(load.writable);
    EXPECT_TRUE(load.entries.empty());
    EXPECT_NE(load.warning.find("history file '" + link + "': it is a symbolic link"),
              std::string::npos)
        << load.warning;
    const std::string refused = apcictl::save_history(link, Strings{"status"});
    EXPECT_NE(refused.find("it is not a regular file; it is not written"), std::string::npos)
        << refused;
    EXPECT_EQ(read(target), "precious\n");
    EXPECT_TRUE(std::filesystem::is_symlink(link));
}

TEST_F(ShellHistory, ADirectoryOrAFifoIsNeitherReadNorWritten) {
    const std::string dir = path("dir");
    std::filesystem::create_directory(dir);
    const auto load = apcictl::load_history(dir);
    EXPECT_FALSE(load.writable);
    EXPECT_NE(load.warning.find("it is not a regular file"), std::string::npos) << load.warning;
    EXPECT_NE(apcictl::save_history(dir, Strings{"status"}), "");
    EXPECT_TRUE(std::filesystem::is_directory(dir));

    const std::string fifo = path("fifo");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const auto from_fifo = apcictl::load_history(fifo);  // returns at once: no writer needed
    EXPECT_FALSE(from_fifo.writable);
    EXPECT_NE(from_fifo.warning.find("it is not a regular file"), std::string::npos);
}

TEST_F(ShellHistory, AnOversizedFileIsNeitherReadNorWritten) {
    const std::string file = path("big");
    write(file, std::string(apcictl::kHistoryFileLimit + 1, 'x'));
    const auto load = apcictl::load_history(file);
    EXPECT_FALSE(load.writable);
    EXPECT_NE(load.warning.find("larger than"), std::string::npos) << load.warning;
    EXPECT_EQ(std::filesystem::file_size(file), apcictl::kHistoryFileLimit + 1);
}

TEST_F(ShellHistory, AnotherUsersFileIsNeitherReadNorWritten) {
    if (::geteuid() != 0) GTEST_SKIP() << "giving a file to another user needs root";
    const std::string file = path("theirs");
    write(file, "their line\n");
    ASSERT_EQ(::chown(file.c_str(), 65534, 65534), 0);
    const auto load = apcictl::load_history(file);
    EXPECT_FALSE(load.writable);
    EXPECT_TRUE(load.entries.empty());
    EXPECT_NE(load.warning.find("it belongs to another user"), std::string::npos) << load.warning;
    const std::string refused = apcictl::save_history(file, Strings{"status"});
    EXPECT_NE(refused.find("it belongs to another user; it is not written"), std::string::npos)
        << refused;
    EXPECT_EQ(read(file), "their line\n");
}

TEST_F(ShellHistory, APathThroughAFileIsAWarning) {
    const std::string file = path("file");
    write(file, "x\n");
    const std::string warning = apcictl::save_history(file + "/apci/h", Strings{"status"});
    EXPECT_EQ(warning, "history file '" + file + "/apci/h': Not a directory");
    EXPECT_EQ(read(file), "x\n");
}

// ---- the plain reader of piped lines

struct Input {
    explicit Input(std::string text) : text_(std::move(text)) {
        file_ = ::fmemopen(text_.data(), text_.size(), "r");
    }
    ~Input() { std::fclose(file_); }
    Input(const Input&) = delete;
    Input& operator=(const Input&) = delete;
    std::string text_;
    std::FILE* file_ = nullptr;
};

TEST(ShellPlainLines, LinesWithAndWithoutTheLastNewline) {
    using Kind = apcictl::PlainLine::Kind;
    Input in("read 1 2 3 4\r\n\nstatus");
    auto line = apcictl::read_plain_line(in.file_, 100);
    EXPECT_EQ(line.kind, Kind::kLine);
    EXPECT_EQ(line.text, "read 1 2 3 4");
    line = apcictl::read_plain_line(in.file_, 100);
    EXPECT_EQ(line.kind, Kind::kLine);
    EXPECT_EQ(line.text, "");
    line = apcictl::read_plain_line(in.file_, 100);
    EXPECT_EQ(line.kind, Kind::kLine);
    EXPECT_EQ(line.text, "status");
    EXPECT_EQ(apcictl::read_plain_line(in.file_, 100).kind, Kind::kEnd);
}

TEST(ShellPlainLines, ALongLineIsReadToItsEndButNotKept) {
    using Kind = apcictl::PlainLine::Kind;
    Input in(std::string(50, 'x') + "\nstatus\n");
    auto line = apcictl::read_plain_line(in.file_, 10);
    EXPECT_EQ(line.kind, Kind::kTooLong);
    EXPECT_EQ(line.text, std::string(10, 'x'));
    line = apcictl::read_plain_line(in.file_, 10);
    EXPECT_EQ(line.kind, Kind::kLine);
    EXPECT_EQ(line.text, "status");
}

}  // namespace
