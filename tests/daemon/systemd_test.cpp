// SPDX-License-Identifier: MIT
// rwmos-emu under systemd (docs/rwmos-emu.md, "As a systemd user service"): a listening socket
// passed by socket activation (LISTEN_FDS, sd_listen_fds(3)) is served and left in place, and
// log lines carry their syslog priority when stderr is the journal ($JOURNAL_STREAM), else not.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apci/apci.hpp"
#include "daemon.h"
#include "process.h"
#include "text.h"

namespace {

using test_support::read_text;
using apci_test::daemon_binary;
using apci_test::eventually;
using apci_test::TempDir;

// A descriptor closed when the test ends, however it ends.
struct OwnedFd {
    int fd = -1;
    ~OwnedFd() {
        if (fd >= 0) ::close(fd);
    }
};

// A listening Unix stream socket bound at `path`, as a .socket unit makes it.
int listening_socket(const std::string& path) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    if (fd < 0 || ::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 ||
        ::listen(fd, 16) != 0)
        return -1;
    return fd;
}

struct Child {
    pid_t pid = -1;
    // Waits for the exit (SIGKILL after 10 s); the exit code, 128+N for signal N.
    int wait() {
        int status = 0;
        for (int i = 0; i < 1000; ++i) {
            if (::waitpid(pid, &status, WNOHANG) == pid)
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            ::usleep(10'000);
        }
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        return -1;
    }
};

// How the descriptors are handed over: systemd's way (LISTEN_FDS=1, LISTEN_PID = the daemon's
// pid), or with `count` sockets (fd 3 .. 3+count-1, each a copy of the one given), or meant for
// another process (LISTEN_PID = its parent's pid, as when a service's child inherits them).
struct Handover {
    int count = 1;
    bool for_the_daemon = true;
};

// Starts rwmos-emu with `args`, stderr to `log`, in `dir`'s registry; `listen_fd` >= 0 is
// handed over as systemd does (fd 3, LISTEN_FDS=1, LISTEN_PID = the daemon's pid);
// `journal_stream`, when set, becomes $JOURNAL_STREAM.
Child spawn(const std::vector<std::string>& args, const TempDir& dir, const std::string& log,
            int listen_fd, const std::string& journal_stream = {}, Handover handover = {}) {
    Child c;
    const pid_t parent = ::getpid();
    c.pid = ::fork();
    if (c.pid == 0) {
        const int err = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        ::dup2(err, 2);
        if (listen_fd >= 0) {
            for (int i = 0; i < handover.count; ++i) ::dup2(listen_fd, 3 + i);
            ::setenv("LISTEN_FDS", std::to_string(handover.count).c_str(), 1);
            ::setenv("LISTEN_PID",
                     std::to_string(handover.for_the_daemon ? ::getpid() : parent).c_str(), 1);
        }
        if (!journal_stream.empty()) {
            ::setenv("JOURNAL_STREAM", journal_stream.c_str(), 1);
        } else {
            ::unsetenv("JOURNAL_STREAM");
        }
        ::setenv("APCI_RUNTIME_DIR", dir.path().c_str(), 1);
        std::vector<char*> argv{const_cast<char*>(daemon_binary())};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    return c;
}

TEST(RwmosEmuSystemd, ServesTheSocketSystemdPassedAndLeavesItInPlace) {
    TempDir dir;
    const std::string path = dir.file("activated.sock");
    const OwnedFd socket{listening_socket(path)};
    const int fd = socket.fd;
    ASSERT_GE(fd, 0) << std::strerror(errno);
    Child daemon = spawn({"--log-level", "info"}, dir, dir.file("log"), fd);
    // The socket listens before the daemon runs: a client may connect at once, as under systemd.
    apci::Board board("unix:" + path);
    ASSERT_TRUE(board) << board.last_error();
    auto radius = apci::object(1300, 1, 1, 7);
    ASSERT_TRUE(board.write_double(radius, 2.5)) << board.last_error();
    const auto read = board.read_double(radius);
    ASSERT_TRUE(read) << board.last_error();
    EXPECT_EQ(read.value, 2.5);
    board = apci::Board();
    ::kill(daemon.pid, SIGTERM);
    EXPECT_EQ(daemon.wait(), 0);
    const std::string log = read_text(dir.file("log"));
    EXPECT_NE(log.find("on socket (from systemd) " + path), std::string::npos) << log;
    // The .socket unit owns the file: still there, and still the socket systemd listens on.
    struct stat st {};
    ASSERT_EQ(::lstat(path.c_str(), &st), 0) << "the daemon removed systemd's socket";
    EXPECT_TRUE(S_ISSOCK(st.st_mode));
}

TEST(RwmosEmuSystemd, SocketOptionMustNameThePassedSocket) {
    TempDir dir;
    const OwnedFd socket{listening_socket(dir.file("activated.sock"))};
    const int fd = socket.fd;
    ASSERT_GE(fd, 0);
    // --socket naming the same path: served (the unit's ExecStart works with and without the
    // .socket unit).
    Child same = spawn({"--socket", dir.file("activated.sock")}, dir, dir.file("log1"), fd);
    ASSERT_TRUE(eventually([&] {
        return read_text(dir.file("log1")).find("from systemd") != std::string::npos;
    }));
    ::kill(same.pid, SIGTERM);
    EXPECT_EQ(same.wait(), 0);
    // Another path: refused, naming both; neither file is touched.
    Child other = spawn({"--socket", dir.file("other.sock")}, dir, dir.file("log2"), fd);
    EXPECT_EQ(other.wait(), 1);
    const std::string log = read_text(dir.file("log2"));
    EXPECT_NE(log.find("the socket passed by systemd is " + dir.file("activated.sock") +
                       ", not --socket " + dir.file("other.sock")),
              std::string::npos)
        << log;
    struct stat st {};
    EXPECT_NE(::lstat(dir.file("other.sock").c_str(), &st), 0);
    EXPECT_EQ(::lstat(dir.file("activated.sock").c_str(), &st), 0);
}

TEST(RwmosEmuSystemd, PassedFdThatIsNotAListeningSocketIsRefused) {
    TempDir dir;
    const OwnedFd plain{::open(dir.file("plain").c_str(), O_RDWR | O_CREAT, 0600)};
    const int fd = plain.fd;
    ASSERT_GE(fd, 0);
    Child daemon = spawn({}, dir, dir.file("log"), fd);
    EXPECT_EQ(daemon.wait(), 1);
    EXPECT_NE(read_text(dir.file("log")).find("systemd (fd 3)"), std::string::npos)
        << read_text(dir.file("log"));
}

// sd_listen_fds(3): the variables count only for the process LISTEN_PID names. A socket passed
// to another process (the daemon inherited it) is not taken: the daemon binds --socket itself.
TEST(RwmosEmuSystemd, SocketPassedToAnotherProcessIsNotTaken) {
    TempDir dir;
    const OwnedFd socket{listening_socket(dir.file("activated.sock"))};
    ASSERT_GE(socket.fd, 0) << std::strerror(errno);
    Child daemon = spawn({"--socket", dir.file("own.sock")}, dir, dir.file("log"), socket.fd, {},
                         Handover{1, false});
    ASSERT_TRUE(eventually([&] {
        return read_text(dir.file("log")).find("serving one board") != std::string::npos;
    })) << read_text(dir.file("log"));
    apci::Board board("unix:" + dir.file("own.sock"));
    EXPECT_TRUE(board) << board.last_error();
    board = apci::Board();
    ::kill(daemon.pid, SIGTERM);
    EXPECT_EQ(daemon.wait(), 0);
    const std::string log = read_text(dir.file("log"));
    EXPECT_EQ(log.find("from systemd"), std::string::npos) << log;
    EXPECT_NE(log.find("on socket " + dir.file("own.sock")), std::string::npos) << log;
}

// One ListenStream= is all the daemon serves: two passed sockets are a usage error (exit 2)
// that says so; one is served (ServesTheSocketSystemdPassedAndLeavesItInPlace).
TEST(RwmosEmuSystemd, MoreThanOnePassedSocketIsAUsageError) {
    TempDir dir;
    const OwnedFd socket{listening_socket(dir.file("activated.sock"))};
    ASSERT_GE(socket.fd, 0) << std::strerror(errno);
    Child daemon = spawn({}, dir, dir.file("log"), socket.fd, {}, Handover{2, true});
    EXPECT_EQ(daemon.wait(), 2);
    EXPECT_NE(read_text(dir.file("log")).find("systemd passed 2 sockets; rwmos-emu serves one"),
              std::string::npos)
        << read_text(dir.file("log"));
}

// An error in the journal carries LOG_ERR's prefix <3> (the other levels: below).
TEST(RwmosEmuSystemd, ErrorLineInTheJournalCarriesPriority3) {
    TempDir dir;
    const std::string log = dir.file("log");
    std::ofstream(log).close();
    struct stat st {};
    ASSERT_EQ(::stat(log.c_str(), &st), 0);
    const std::string stream = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
    Child daemon = spawn({"--socket", dir.file("no-such-dir/s.sock")}, dir, log, -1, stream);
    EXPECT_EQ(daemon.wait(), 1);
    const std::string text = read_text(log);
    EXPECT_EQ(text.rfind("<3>rwmos-emu: error: socket directory " + dir.file("no-such-dir"), 0),
              0u)
        << text;
}

// The journal's stream is stderr when $JOURNAL_STREAM names its device and inode.
TEST(RwmosEmuSystemd, LogLinesCarryTheirPriorityOnlyWhenStderrIsTheJournal) {
    TempDir dir;
    const std::string log = dir.file("log");
    std::ofstream(log).close();
    struct stat st {};
    ASSERT_EQ(::stat(log.c_str(), &st), 0);
    const std::string stream = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
    for (const bool journal : {true, false}) {
        // Emptied here (spawn() truncates it too, later): the inode stays.
        std::ofstream(log, std::ios::trunc).close();
        Child daemon = spawn({"--socket", dir.file("s.sock"), "--log-level", "debug"}, dir, log,
                             -1, journal ? stream : std::string("1:1"));
        ASSERT_TRUE(eventually([&] {
            return read_text(log).find("serving one board") != std::string::npos;
        }));
        // A client that sends garbage: a warning.
        const int c = ::socket(AF_UNIX, SOCK_STREAM, 0);
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        std::strncpy(addr.sun_path, dir.file("s.sock").c_str(), sizeof addr.sun_path - 1);
        ASSERT_EQ(::connect(c, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0)
            << std::strerror(errno) << " journal " << journal << "\n" << read_text(log);
        ASSERT_EQ(::write(c, "garbage!garbage!garbage!", 24), 24);
        ASSERT_TRUE(eventually(
            [&] { return read_text(log).find("garbage") != std::string::npos; }));
        ::close(c);
        ::kill(daemon.pid, SIGTERM);
        EXPECT_EQ(daemon.wait(), 0);
        const std::string text = read_text(log);
        std::istringstream lines(text);
        int seen = 0;
        for (std::string line; std::getline(lines, line); ++seen) {
            SCOPED_TRACE(line);
            const auto level_at = line.find("rwmos-emu: ");
            ASSERT_NE(level_at, std::string::npos);
            const std::string prefix = line.substr(0, level_at);
            const std::string level = line.substr(level_at + 11, line.find(':', level_at + 11) -
                                                                     level_at - 11);
            if (!journal) {
                EXPECT_EQ(prefix, "");
                continue;
            }
            const std::string want = level == "error"  ? "<3>"
                                     : level == "warn" ? "<4>"
                                     : level == "info" ? "<6>"
                                                       : "<7>";
            EXPECT_EQ(prefix, want);
        }
        EXPECT_GE(seen, 3);
        if (journal) {
            EXPECT_NE(text.find("<4>rwmos-emu: warn: "), std::string::npos) << text;
            EXPECT_NE(text.find("<6>rwmos-emu: info: "), std::string::npos) << text;
            EXPECT_NE(text.find("<7>rwmos-emu: debug: "), std::string::npos) << text;
        }
    }
}

TEST(RwmosEmuSystemd, VersionNamesProgramPackageAndVersion) {
    std::string output;
    TempDir dir;
    EXPECT_EQ(apci_test::run_daemon({"--version"}, output, dir.path()), 0);
    EXPECT_EQ(output, std::string("rwmos-emu (apci8001) ") + APCI8001_VERSION + "\n");
}

// --version and --help whose standard output cannot take the text (a full device, a closed
// descriptor): exit 1 saying so, as apcictl does, not 0 as if it had been printed.
TEST(RwmosEmuSystemd, VersionAndHelpThatCannotBeWrittenExitOne) {
    for (const char* option : {"--version", "--help"}) {
        for (const auto& [redirect, reason] :
             {std::pair<std::string, std::string>{">/dev/full", "No space left on device"},
              {">&-", "Bad file descriptor"}}) {
            SCOPED_TRACE(std::string(option) + " " + redirect);
            const auto r = test_support::run_process(
                {"/bin/sh", "-c", std::string("exec \"$0\" ") + option + " " + redirect,
                 apci_test::daemon_binary()});
            EXPECT_EQ(r.exit_code, 1);
            EXPECT_EQ(r.err, "rwmos-emu: cannot write standard output: " + reason + "\n");
        }
    }
}

}  // namespace
