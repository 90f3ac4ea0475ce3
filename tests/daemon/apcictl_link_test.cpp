// SPDX-License-Identifier: MIT
// apcictl against a daemon whose link goes away: every command's error says why (the daemon's
// words, not only the status name), the shell opens a link the daemon closed while it waited
// for a line again, `run` publishes no output of a run the daemon's death cut short, and a
// program from a pipe is read once (docs/apcictl.md).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon.h"
#include "process.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::names_in;
using test_support::read_text;
using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::TempDir;
using namespace std::chrono_literals;

// apcictl with its standard input fed line by line and its output read as it comes.
class Apcictl {
  public:
    explicit Apcictl(const std::vector<std::string>& args, const std::string& cwd = {}) {
        int in[2], out[2], err[2];
        if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0 ||
            ::pipe2(err, O_CLOEXEC) != 0)
            return;
        pid_ = ::fork();
        if (pid_ == 0) {
            ::dup2(in[0], 0);
            ::dup2(out[1], 1);
            ::dup2(err[1], 2);
            if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(126);
            std::vector<char*> argv{const_cast<char*>(APCICTL_PATH)};
            for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
            argv.push_back(nullptr);
            ::execv(argv[0], argv.data());
            ::_exit(127);
        }
        ::close(in[0]);
        ::close(out[1]);
        ::close(err[1]);
        in_ = in[1];
        out_ = out[0];
        err_ = err[0];
    }
    ~Apcictl() {
        for (const int fd : {in_, out_, err_})
            if (fd >= 0) ::close(fd);
        if (pid_ > 0 && !waited_) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    Apcictl(const Apcictl&) = delete;
    Apcictl& operator=(const Apcictl&) = delete;

    pid_t pid() const noexcept { return pid_; }
    bool send(const std::string& text) {
        return ::write(in_, text.data(), text.size()) == static_cast<ssize_t>(text.size());
    }
    // Reads standard output until it holds `text` (at most `limit`).
    bool output_has(const std::string& text, std::chrono::milliseconds limit = 30s) {
        const auto until = std::chrono::steady_clock::now() + limit;
        while (!contains(out_text_, text)) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                until - std::chrono::steady_clock::now());
            if (left.count() <= 0) return false;
            pollfd p{out_, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
            char buf[4096];
            const ssize_t n = ::read(out_, buf, sizeof buf);
            if (n <= 0) return false;
            out_text_.append(buf, static_cast<std::size_t>(n));
        }
        return true;
    }
    // Ends standard input, reads the rest and waits: the exit code (-1: a signal).
    int finish() {
        ::close(in_);
        in_ = -1;
        drain(out_, out_text_);
        drain(err_, err_text_);
        int status = 0;
        ::waitpid(pid_, &status, 0);
        waited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    const std::string& out() const noexcept { return out_text_; }
    const std::string& err() const noexcept { return err_text_; }

  private:
    static void drain(int fd, std::string& text) {
        char buf[4096];
        for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;)
            text.append(buf, static_cast<std::size_t>(n));
    }

    pid_t pid_ = -1;
    int in_ = -1, out_ = -1, err_ = -1;
    bool waited_ = false;
    std::string out_text_, err_text_;
};

// A daemon closes a link idle for its --idle-timeout: the shell, waiting for its next line
// meanwhile, opens the link again before it runs that line and says so (every later line
// failed: "TransportError (transport to the board failed)").
TEST(ApcictlLink, TheShellOpensALinkTheDaemonClosedWhileIdleAgain) {
    DaemonOptions o;
    o.extra_args = {"--idle-timeout", "1"};
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    Apcictl shell({"--device", d->unix_uri(), "shell"});
    ASSERT_TRUE(shell.send("write 1300 0 20 0 1.5\nread 1300 0 20 0\n"));
    ASSERT_TRUE(shell.output_has("1.5\n")) << shell.out();
    ASSERT_TRUE(apci_test::eventually([&] { return contains(d->log(), "idle for 1 s"); }))
        << d->log();
    ASSERT_TRUE(shell.send("read 1300 0 20 0\nwrite 1300 0 20 0 2.5\nread 1300 0 20 0\n"));
    EXPECT_EQ(shell.finish(), 0) << shell.err();
    EXPECT_EQ(shell.out(), "1.5\n1.5\n2.5\n");
    // Every link the daemon closed and the shell used again is opened again and noted once:
    // the closure waited for above, and on a loaded machine perhaps one more (the shell's
    // first request more than a second after it opened the link). No more notes than the
    // daemon closed links idle, and nothing else said.
    const std::string note = "apcictl: note: the link to " + d->unix_uri() +
                             " had been closed (a daemon closes a link idle for its "
                             "--idle-timeout); opened again\n";
    const std::size_t notes = test_support::count_of(shell.err(), note);
    EXPECT_GE(notes, 1u) << shell.err();
    EXPECT_LE(notes, test_support::count_of(d->log(), "idle for 1 s")) << d->log();
    std::string all_notes;
    for (std::size_t i = 0; i < notes; ++i) all_notes += note;
    EXPECT_EQ(shell.err(), all_notes);
}

// A link the daemon closed (it shut down): every kind of command says the daemon's words after
// the status, in the shell (and so in a script, which reports the same lines).
TEST(ApcictlLink, EveryCommandSaysWhyTheLinkFailed) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    Apcictl shell({"--device", d->unix_uri(), "shell"});
    ASSERT_TRUE(shell.send("read 1000 0 3 0\n"));
    ASSERT_TRUE(shell.output_has("8\n")) << shell.out();
    ASSERT_EQ(d->stop(), 0);
    const std::vector<std::string> lines = {
        "read 1000 0 3 0",   "write 1300 0 20 0 1.5", "status",     "step 5",
        "spool G01 X1 F100", "direct JA X1 F100",     "ssf X 2001",
    };
    for (const auto& line : lines) ASSERT_TRUE(shell.send(line + "\n"));
    EXPECT_EQ(shell.finish(), 1);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string head = "apcictl: line " + std::to_string(i + 2) + ": ";
        const auto at = shell.err().find(head);
        ASSERT_NE(at, std::string::npos) << lines[i] << "\n" << shell.err();
        const std::string said = shell.err().substr(at, shell.err().find('\n', at) - at);
        EXPECT_TRUE(contains(said, "TransportError (transport to the board failed): ")) << said;
        EXPECT_TRUE(contains(said, "closed the connection: shutting down (SIGTERM)")) << said;
        // apcictl's hint, not the C API's: its user cannot call apci_reconnect().
        EXPECT_FALSE(contains(said, "apci_reconnect")) << said;
        EXPECT_TRUE(said.ends_with("; the next command opens the link again")) << said;
    }
}

// A program from a pipe on a daemon's board (validated, then run: two passes) is read once;
// the second pass found the pipe empty and said the program ends without M30.
TEST(ApcictlRunOnADaemon, AProgramFromAPipeIsReadOnce) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    const auto r = test_support::run_process(
        {APCICTL_PATH, "--device", d->unix_uri(), "run", "/dev/stdin", "--json", "-"},
        "N10 G1 X10 F600\nM30\n");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "\"block\":10")) << r.out;
    EXPECT_TRUE(contains(r.err, "/dev/stdin: 2 blocks, 2 sent to the board, 1 segment executed")) << r.err;
}

// The daemon killed in the middle of a run: the run did not finish, so nothing of it replaces
// the old outputs (a JSON with a TransportError and a 44 MB CSV were published over them), no
// temporary file stays, and the message says so and why.
TEST(ApcictlRunOnADaemon, ADaemonKilledMidRunPublishesNoOutput) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    TempDir dir;
    std::ofstream(dir.file("long.nc")) << "N10 G1 X1000 F60\nM30\n";  // a million cycles
    std::ofstream(dir.file("out.json")) << "old json\n";
    std::ofstream(dir.file("out.csv")) << "old csv\n";
    Apcictl run(
        {"--device", d->unix_uri(), "run", "long.nc", "--json", "out.json", "--csv", "out.csv"},
        dir.path());
    bool under_way = false;
    for (int i = 0; i < 3000 && !under_way; ++i) {
        for (const std::string& name : names_in(dir.path())) {
            struct stat st {};
            if (name.starts_with(".out.csv.apcictl-") && ::stat(dir.file(name).c_str(), &st) == 0 &&
                st.st_size > (1 << 20))
                under_way = true;
        }
        if (!under_way) std::this_thread::sleep_for(10ms);
    }
    ASSERT_TRUE(under_way);
    ASSERT_EQ(::kill(d->pid(), SIGKILL), 0);
    EXPECT_EQ(run.finish(), 1) << run.err();
    EXPECT_TRUE(contains(run.err(),
                         "apcictl: run long.nc: no output written (any old ones are "
                         "kept): the run did not finish"))
        << run.err();
    EXPECT_TRUE(contains(run.err(), "TransportError")) << run.err();
    // One block, run by the clock: the error is the clock's, of no block ("stopped at -" was
    // said of it).
    EXPECT_TRUE(contains(run.err(), "apcictl: run long.nc: stopped: TransportError\n") ||
                contains(run.err(), "apcictl: run long.nc: stopped at line 1 (N10): TransportError\n"))
        << run.err();
    EXPECT_EQ(read_text(dir.file("out.json")), "old json\n");
    EXPECT_EQ(read_text(dir.file("out.csv")), "old csv\n");
    std::set<std::string> left = names_in(dir.path());
    for (auto it = left.begin(); it != left.end();)
        it = it->starts_with("rwmos-emu.") || it->ends_with(".lock") ? left.erase(it) : ++it;
    EXPECT_EQ(left, (std::set<std::string>{"long.nc", "out.json", "out.csv"}));
    d->stop();
}

}  // namespace
