// SPDX-License-Identifier: MIT
// apcictl shell as a process: on a pseudo-terminal (TAB completion, a failing line that does
// not end the session, Up recalling a line, Ctrl-D, the history file) and from a pipe (one
// session, errors named by line, the exit code). Every wait is bounded.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "apcictl.h"
#include "text.h"

namespace {

using test_support::read_text;
using Env = std::vector<std::pair<std::string, std::string>>;
constexpr int kWaitMs = 20000;  // generous for a loaded machine; a pass takes milliseconds

// apcictl on a pseudo-terminal: type into it, wait (bounded) for what it shows.
class Terminal {
  public:
    Terminal(const std::vector<std::string>& args, const Env& env) {
        winsize size{};
        size.ws_row = 24;
        size.ws_col = 80;
        pid_ = ::forkpty(&master_, nullptr, nullptr, &size);
        if (pid_ == 0) {
            ::setenv("TERM", "xterm", 1);
            ::unsetenv("XDG_STATE_HOME");
            ::unsetenv("APCI_DEVICE");
            for (const auto& [name, value] : env) ::setenv(name.c_str(), value.c_str(), 1);
            std::vector<char*> argv{const_cast<char*>(APCICTL_PATH)};
            for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
            argv.push_back(nullptr);
            ::execv(argv[0], argv.data());
            ::_exit(127);
        }
    }
    ~Terminal() {
        if (pid_ > 0 && !reaped_) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
        if (master_ >= 0) ::close(master_);
    }
    Terminal(const Terminal&) = delete;
    Terminal& operator=(const Terminal&) = delete;

    bool started() const { return pid_ > 0 && master_ >= 0; }

    void type(std::string_view keys) {
        while (!keys.empty()) {
            const ssize_t n = ::write(master_, keys.data(), keys.size());
            if (n <= 0) return;
            keys.remove_prefix(static_cast<std::size_t>(n));
        }
    }

    // Waits until `text` shows after what earlier waits consumed; consumes up to its end.
    bool wait_for(std::string_view text) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kWaitMs);
        for (;;) {
            const auto found = output_.find(text, consumed_);
            if (found != std::string::npos) {
                consumed_ = found + text.size();
                return true;
            }
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0 || !read_some(static_cast<int>(left.count()))) return false;
        }
    }

    // Waits (bounded) for the process to end; its exit code, -1 if killed or still running.
    int wait_exit() {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kWaitMs);
        while (std::chrono::steady_clock::now() < deadline) {
            read_some(50);  // drain, so it never blocks writing to the terminal
            int status = 0;
            const pid_t done = ::waitpid(pid_, &status, WNOHANG);
            if (done == pid_) {
                reaped_ = true;
                return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
            }
        }
        return -1;
    }

    // Waits for the prompt and for the line editor to take the terminal over (no echo by the
    // terminal itself): keys typed before that would be echoed twice.
    bool wait_for_prompt() {
        if (!wait_for("apcictl> ")) return false;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kWaitMs);
        while (std::chrono::steady_clock::now() < deadline) {
            termios mode{};
            if (::tcgetattr(master_, &mode) == 0 && (mode.c_lflag & (ECHO | ICANON)) == 0)
                return true;
            read_some(5);
        }
        return false;
    }

    // Waits until the line the cursor is on reads `text` (escape sequences applied).
    bool wait_for_line(std::string_view text) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kWaitMs);
        for (;;) {
            if (current_line() == text) return true;
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0 || !read_some(static_cast<int>(left.count()))) return false;
        }
    }

    // The last line of the output as a terminal shows it: carriage return, backspace and the
    // cursor movements and erasing libedit uses (CSI n G, C, D, K) applied.
    std::string current_line() const {
        const std::size_t newline = output_.rfind('\n');
        const std::string_view raw =
            std::string_view(output_).substr(newline == std::string::npos ? 0 : newline + 1);
        std::string line;
        std::size_t cursor = 0;
        for (std::size_t i = 0; i < raw.size(); ++i) {
            const char c = raw[i];
            if (c == '\r') {
                cursor = 0;
            } else if (c == '\b') {
                if (cursor > 0) --cursor;
            } else if (c == '\x1b' && i + 1 < raw.size() && raw[i + 1] == '[') {
                std::size_t j = i + 2;
                std::size_t n = 0;
                bool has_n = false;
                while (j < raw.size() && raw[j] >= '0' && raw[j] <= '9') {
                    n = n * 10 + static_cast<std::size_t>(raw[j] - '0');
                    has_n = true;
                    ++j;
                }
                if (j >= raw.size()) break;
                const std::size_t count = has_n ? n : 1;
                if (raw[j] == 'G') cursor = count - 1;
                if (raw[j] == 'C') cursor += count;
                if (raw[j] == 'D') cursor -= std::min(cursor, count);
                if (raw[j] == 'K') line.resize(std::min(line.size(), cursor));
                i = j;
            } else if (static_cast<unsigned char>(c) >= 0x20) {
                if (line.size() <= cursor) line.resize(cursor + 1, ' ');
                line[cursor++] = c;
            }
        }
        return line;
    }

    // The output so far with control characters spelt out (for failure messages).
    std::string output() const {
        std::string text;
        for (const char c : output_) {
            if (c == '\n')
                text += "\\n\n";
            else if (static_cast<unsigned char>(c) < 0x20)
                text += "^" + std::string(1, static_cast<char>(c + 64));
            else
                text += c;
        }
        return text;
    }

  private:
    bool read_some(int timeout_ms) {
        pollfd fd{master_, POLLIN, 0};
        if (::poll(&fd, 1, timeout_ms) <= 0) return false;
        char buffer[4096];
        const ssize_t n = ::read(master_, buffer, sizeof buffer);
        if (n <= 0) return false;  // EIO once the child closed the terminal
        output_.append(buffer, static_cast<std::size_t>(n));
        return true;
    }

    pid_t pid_ = -1;
    int master_ = -1;
    bool reaped_ = false;
    std::string output_;
    std::size_t consumed_ = 0;
};

class ApcictlShell : public ::testing::Test {
  protected:
    void SetUp() override {
        char pattern[] = "/tmp/apcictl_shell_test.XXXXXX";
        ASSERT_NE(::mkdtemp(pattern), nullptr);
        dir_ = pattern;
        env_ = {{"HOME", dir_}, {"APCI_HISTORY", history()}};
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string history() const { return dir_ + "/history"; }

    test_support::ProcessResult piped(const std::string& input,
                                      const std::vector<std::string>& args = {"shell"}) {
        return test_support::apcictl(args, input, env_);
    }

    std::string dir_;
    Env env_;
};

// ---- on a terminal

TEST_F(ApcictlShell, TerminalCompletesSurvivesAFailureRecallsAndEndsOnCtrlD) {
    Terminal terminal({"shell"}, env_);
    ASSERT_TRUE(terminal.started());
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();

    // A partial command and TAB: completed, with a blank after it.
    terminal.type("rea\t");
    ASSERT_TRUE(terminal.wait_for_line("apcictl> read ")) << terminal.output();
    // ... finished into a line that fails: the error, and the session goes on.
    terminal.type("1300 1 9 3\r");
    ASSERT_TRUE(terminal.wait_for("apcictl: read 1300 1 9 3: ObjectMissing")) << terminal.output();
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();

    // State carries from line to line: one board for the whole shell.
    terminal.type("write 1300 1 1 7 2.5\r");
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();
    terminal.type("read 1300 1 1 7\r");
    ASSERT_TRUE(terminal.wait_for("\n2.5\r\n")) << terminal.output();
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();

    // Up recalls the last line; Enter runs it again.
    terminal.type("\x1b[A");
    ASSERT_TRUE(terminal.wait_for_line("apcictl> read 1300 1 1 7")) << terminal.output();
    terminal.type("\r");
    ASSERT_TRUE(terminal.wait_for("\n2.5\r\n")) << terminal.output();
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();

    // Ctrl-D on an empty line ends the shell; a line failed, so the exit code is 1.
    terminal.type("\x04");
    EXPECT_EQ(terminal.wait_exit(), 1) << terminal.output();

    // The history file holds the lines, the recalled one once.
    EXPECT_EQ(read_text(history()), "read 1300 1 9 3\nwrite 1300 1 1 7 2.5\nread 1300 1 1 7\n");
    struct stat st {};
    ASSERT_EQ(::stat(history().c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
}

TEST_F(ApcictlShell, TerminalListsSeveralCandidatesAndRecallsTheFileHistory) {
    std::ofstream(history()) << "write 1300 1 1 8 5\n";
    Terminal terminal({"shell"}, env_);
    ASSERT_TRUE(terminal.started());
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();

    // "st" extends to nothing more: TAB lists status and step.
    terminal.type("st\t");
    ASSERT_TRUE(terminal.wait_for("status  step")) << terminal.output();
    terminal.type("ep 1\r");  // the line is still there after the list
    ASSERT_TRUE(terminal.wait_for("cycle 1 (+1)")) << terminal.output();
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();

    // Up twice: past "step 1", the line of the previous session.
    terminal.type("\x1b[A\x1b[A");
    ASSERT_TRUE(terminal.wait_for_line("apcictl> write 1300 1 1 8 5")) << terminal.output();
    terminal.type("\r");
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();
    terminal.type("read 1300 1 1 8\r");
    ASSERT_TRUE(terminal.wait_for("\n5\r\n")) << terminal.output();
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();

    // Object names of the map complete one part at a time; Ctrl-U then clears the line.
    terminal.type("read tc.gr\t");
    ASSERT_TRUE(terminal.wait_for_line("apcictl> read tc.group[")) << terminal.output();
    terminal.type("1].rad\t");
    ASSERT_TRUE(terminal.wait_for_line("apcictl> read tc.group[1].radius ")) << terminal.output();
    terminal.type("\x15");
    ASSERT_TRUE(terminal.wait_for_line("apcictl> ")) << terminal.output();

    terminal.type("quit\r");
    EXPECT_EQ(terminal.wait_exit(), 0) << terminal.output();
    EXPECT_EQ(read_text(history()),
              "write 1300 1 1 8 5\nstep 1\nwrite 1300 1 1 8 5\nread 1300 1 1 8\nquit\n");
}

TEST_F(ApcictlShell, TerminalWithAHistoryLinkWarnsAndLeavesItAlone) {
    const std::string target = dir_ + "/precious";
    std::ofstream(target) << "not a history\n";
    ASSERT_EQ(::symlink(target.c_str(), history().c_str()), 0);
    Terminal terminal({"shell"}, env_);
    ASSERT_TRUE(terminal.started());
    ASSERT_TRUE(terminal.wait_for("apcictl: warning: history file '" + history() +
                                  "': it is a symbolic link"))
        << terminal.output();
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();
    terminal.type("read 1300 1 1 7\r");
    ASSERT_TRUE(terminal.wait_for("\n0\r\n")) << terminal.output();
    // Ctrl-D typed ahead, while the terminal is still in cooked mode, would reach the line
    // editor as a NUL byte (the line discipline turns a pending EOF into one when the mode
    // changes): wait until the editor holds the terminal again.
    ASSERT_TRUE(terminal.wait_for_prompt()) << terminal.output();
    terminal.type("\x04");
    EXPECT_EQ(terminal.wait_exit(), 0) << terminal.output();
    EXPECT_EQ(read_text(target), "not a history\n");
    EXPECT_TRUE(std::filesystem::is_symlink(history()));
}

// The line editor is loaded only by the shell on a terminal; where it cannot be (here a
// libedit.so.2 that is no library, found first through LD_LIBRARY_PATH) the shell says so and
// reads plain lines.
TEST_F(ApcictlShell, TerminalWithoutALoadableLineEditorWarnsAndReadsPlainLines) {
    const std::string lib = dir_ + "/lib";
    ASSERT_TRUE(std::filesystem::create_directory(lib));
    std::ofstream(lib + "/libedit.so.2") << "not a library\n";
    Env env = env_;
    env.emplace_back("LD_LIBRARY_PATH", lib);
    Terminal terminal({"shell"}, env);
    ASSERT_TRUE(terminal.started());
    ASSERT_TRUE(terminal.wait_for("apcictl: warning: the line editor could not be loaded (" + lib +
                                  "/libedit.so.2"))
        << terminal.output();
    ASSERT_TRUE(
        terminal.wait_for("); lines are read as typed, without editing, history or "
                          "completion"))
        << terminal.output();
    terminal.type("write 1300 1 1 7 2.5\rread 1300 1 1 7\r");
    ASSERT_TRUE(terminal.wait_for("\n2.5\r\n")) << terminal.output();
    terminal.type("\x04");  // the terminal's own end of input: no editor holds it
    EXPECT_EQ(terminal.wait_exit(), 0) << terminal.output();
    EXPECT_FALSE(std::filesystem::exists(history()));  // no history without the editor
}

// ---- from a pipe

TEST_F(ApcictlShell, PipedLinesShareOneSessionAndErrorsDoNotEndIt) {
    const auto r = piped(
        "write 1300 1 1 7 2.5\n"
        "raed 1300 1 1 7\n"
        "\n"
        "# a comment\n"
        "read 1300 1 9 3\n"
        "read 1300 1 1 7   # after two failures\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "2.5\n");  // no prompt, no echo
    EXPECT_EQ(r.err,
              "apcictl: line 2: unknown command 'raed'; did you mean 'read'?\n"
              "apcictl: line 5: read 1300 1 9 3: ObjectMissing (object index does not exist)\n");
    EXPECT_FALSE(std::filesystem::exists(history()));  // no history from a pipe
}

TEST_F(ApcictlShell, PipedWithoutFailureExitsZeroAndQuitEndsIt) {
    const auto r = piped("write 1300 1 1 8 5\nread 1300 1 1 8\nquit\nread 1300 1 1 8\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "5\n");
    EXPECT_EQ(r.err, "");
    const auto empty = piped("");
    EXPECT_EQ(empty.exit_code, 0);
    EXPECT_EQ(empty.out, "");
}

TEST_F(ApcictlShell, StatusAfterEachLineWithTheFlagOrStatusOn) {
    const auto flagged = piped("write 1300 1 1 8 5\n", {"shell", "--status"});
    EXPECT_EQ(flagged.exit_code, 0) << flagged.err;
    EXPECT_EQ(flagged.out.find("board (bus 1000): spooler 0 of 256 profiles\n"), 0u) << flagged.out;
    EXPECT_NE(flagged.out.find("active group: ERROR 0x00 none"), std::string::npos);

    const auto switched = piped(
        "read 1300 1 1 8\nstatus on\nread 1300 1 1 8\nstatus off\n"
        "read 1300 1 1 8\n");
    EXPECT_EQ(switched.exit_code, 0) << switched.err;
    // The status follows the second read only.
    EXPECT_EQ(switched.out.find("0\nboard (bus 1000)"), 2u) << switched.out;
    EXPECT_EQ(switched.out.substr(switched.out.size() - 2), "0\n");
    std::size_t boards = 0;
    for (auto at = switched.out.find("board (bus"); at != std::string::npos;
         at = switched.out.find("board (bus", at + 1))
        ++boards;
    EXPECT_EQ(boards, 1u) << switched.out;

    const auto bad = piped("status maybe\n");
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_EQ(bad.err,
              "apcictl: line 1: status maybe: give 'on' or 'off' (the status after each line), "
              "or nothing (the status now)\n");
}

TEST_F(ApcictlShell, HelpListsTheCommandsAndTheShellWords) {
    const auto r = piped("help\nhelp write\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    for (const char* word : {"read", "write", "status", "spool", "direct", "ssf", "step",
                             "help [COMMAND]", "status on|off", "quit, exit"})
        EXPECT_NE(r.out.find(word), std::string::npos) << word << "\n" << r.out;
    EXPECT_EQ(r.out.find("  run "), std::string::npos) << r.out;  // not a shell command
    EXPECT_NE(r.out.find("VALUE"), std::string::npos) << r.out;   // write's arguments
    const auto words = piped("help quit\n");
    EXPECT_EQ(words.exit_code, 0) << words.err;
    EXPECT_EQ(words.out.rfind("Shell:\n", 0), 0u) << words.out;
    const auto unknown = piped("help frobnicate\n");
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_EQ(
        unknown.err.rfind("apcictl: line 1: help frobnicate: unknown command 'frobnicate'", 0), 0u)
        << unknown.err;
}

TEST_F(ApcictlShell, CommandsThatAreNoShellCommandsAreNamed) {
    const auto r = piped("run x.nc\nquit now\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("apcictl: line 1: 'run' is not a shell command; run 'apcictl run' "
                         "outside the shell"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("apcictl: line 2: quit: takes no arguments\n"), std::string::npos)
        << r.err;
}

TEST_F(ApcictlShell, AnOverlongPipedLineIsAnErrorNotACommand) {
    const auto r = piped("read 1300 1 1 7" + std::string(70000, ' ') + "x\nread 1300 1 1 7\n");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "0\n");
    EXPECT_EQ(r.err.rfind("apcictl: line 1: longer than 65536 characters; not run", 0), 0u)
        << r.err;
}

TEST_F(ApcictlShell, AnUnopenableDeviceEndsTheShellAtOnce) {
    const auto r = piped("read 1300 1 1 7\n", {"--device", "nonsense:", "shell"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err.rfind("apcictl: ", 0), 0u) << r.err;
}

}  // namespace
