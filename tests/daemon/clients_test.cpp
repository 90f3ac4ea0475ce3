// SPDX-License-Identifier: MIT
// rwmos-emu and its clients (docs/rwmos-emu.md, docs/hardening.md "Resource
// limits", docs/wire-frame.md "Notices"): --max-clients counts live clients
// only; idle clients are closed after --idle-timeout; a refused or closed
// client is told why, and libapci and apcictl say it; every signal that would
// end the daemon ends it cleanly; its log counts every Error reply; its
// socket is bound at its own path; apci_list_devices tells a daemon from
// anything else listening on a registered socket.
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "apci/apci.h"
#include "daemon.h"
#include "objif/frame.h"
#include "objif/mailbox.h"
#include "other_user.h"
#include "process.h"
#include "raw_client.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::count_of;
using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::TempDir;
using daemon_test::RawClient;
using namespace std::chrono_literals;

std::unique_ptr<Daemon> start_with(std::vector<std::string> args, bool shm = false) {
    DaemonOptions o;
    o.shm = shm;
    o.extra_args = std::move(args);
    return Daemon::start(o);
}

// One client's whole life: open, read AxisCount, close. The status of the
// first step that failed (open or read), and the library's words for it.
apci_status one_shot_read(const std::string& uri, std::string& why) {
    apci_board* b = nullptr;
    apci_status s = apci_open(uri.c_str(), &b);
    if (s != APCI_OK) {
        why = apci_last_error(nullptr);
        return s;
    }
    apci_object_descriptor o{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    s = apci_read_int(b, &o, &n);
    if (s != APCI_OK) why = apci_last_error(b);
    apci_close(b);
    return s;
}

// The first frame a raw client receives, the greeting included.
bool first_notice(RawClient& client, objif::Notice& notice,
                  std::chrono::milliseconds timeout = 5s) {
    objif::Frame frame;
    if (!client.receive_any(frame, timeout)) return false;
    return frame.opcode == 0xFFFE &&
           objif::decode(frame.payload, notice) == objif::FrameError::kNone;
}

// Closes a descriptor when the test ends, however it ends.
struct Descriptor {
    explicit Descriptor(int f) : fd(f) {}
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int fd;
};

// ---- Point: live clients only, a reason for the refused, idle clients closed

// A client that hung up no longer counts, even when the daemon has not read
// its EOF yet when the next client connects: 3,000 one-shot clients, four at
// a time, never more than four alive, against --max-clients 4. (Counting
// clients that had hung up refused about 3% of them.)
TEST(DaemonClients, OneShotClientsAtTheLimitAreNeverRefused) {
    auto d = start_with({"--max-clients", "4"});
    ASSERT_NE(d, nullptr);
    constexpr int kThreads = 4;
    constexpr int kEach = 750;
    std::atomic<int> failed{0};
    std::vector<std::string> first_failure(kThreads);
    std::vector<std::thread> threads;
    threads.reserve(kThreads);
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            for (int i = 0; i < kEach; ++i) {
                std::string why;
                if (one_shot_read(d->unix_uri(), why) != APCI_OK) {
                    ++failed;
                    if (first_failure[t].empty()) first_failure[t] = why;
                }
            }
        });
    }
    for (auto& t : threads) t.join();
    std::string failures;
    for (const auto& f : first_failure) failures += f + "\n";
    EXPECT_EQ(failed.load(), 0) << failures << d->log();
    EXPECT_EQ(count_of(d->log(), "refused a client"), 0u) << d->log();
}

// The same, deterministic: the limit is full, one client closes, and the
// next one, connecting at once, is served (the hung-up one is reaped first).
TEST(DaemonClients, ClientThatHungUpIsReleasedBeforeTheNextIsRefused) {
    auto d = start_with({"--max-clients", "2", "--log-level", "debug"});
    ASSERT_NE(d, nullptr);
    for (int round = 0; round < 50; ++round) {
        auto a = std::make_unique<RawClient>(d->socket_path());
        RawClient b(d->socket_path());
        objif::Notice na, nb;
        ASSERT_TRUE(first_notice(*a, na));
        ASSERT_TRUE(first_notice(b, nb));
        ASSERT_EQ(na.status, objif::Status::kOk);
        ASSERT_EQ(nb.status, objif::Status::kOk);
        a.reset();  // hangs up; the daemon may not have read its EOF yet
        RawClient c(d->socket_path());
        objif::Notice nc;
        ASSERT_TRUE(first_notice(c, nc)) << "round " << round;
        EXPECT_EQ(nc.status, objif::Status::kOk) << "round " << round << ": " << nc.text;
    }
    EXPECT_EQ(count_of(d->log(), "refused a client"), 0u) << d->log();
}

// A refused client is told why; libapci's open fails naming the daemon and the
// reason, and apcictl prints it.
TEST(DaemonClients, RefusedClientIsToldTooManyClientsAndApcictlSaysSo) {
    auto d = start_with({"--max-clients", "1"});
    ASSERT_NE(d, nullptr);
    apci_board* held = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &held), APCI_OK) << apci_last_error(nullptr);

    RawClient raw(d->socket_path());
    objif::Notice notice;
    ASSERT_TRUE(first_notice(raw, notice));
    EXPECT_EQ(notice.status, objif::Status::kTransportError);
    EXPECT_EQ(notice.text, "too many clients (1)");
    EXPECT_TRUE(raw.closed_by_peer());

    apci_board* b = nullptr;
    EXPECT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_TRANSPORT_ERROR);
    const std::string why = apci_last_error(nullptr);
    EXPECT_TRUE(contains(
        why, "daemon " + d->socket_path() + " refused the connection: too many clients (1)"))
        << why;

    const auto r = test_support::run_process(
        {APCICTL_PATH, "--device", d->unix_uri(), "read", "1000", "0", "3", "0"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(r.err.starts_with("apcictl: ")) << r.err;
    EXPECT_TRUE(contains(
        r.err, "daemon " + d->socket_path() + " refused the connection: too many clients (1)"))
        << r.err;
    apci_close(held);
}

// 64 idle connections no longer lock everyone out for good: after
// --idle-timeout each is told why and closed (a log line each), and new
// clients are served.
TEST(DaemonClients, IdleClientsAreClosedAfterTheIdleTimeoutAndTheirPlacesFreed) {
    auto d = start_with({"--idle-timeout", "1"});
    ASSERT_NE(d, nullptr);
    std::vector<std::unique_ptr<RawClient>> idle;
    for (int i = 0; i < 64; ++i) {
        idle.push_back(std::make_unique<RawClient>(d->socket_path()));
        objif::Notice greeting;
        ASSERT_TRUE(first_notice(*idle.back(), greeting));
        ASSERT_EQ(greeting.status, objif::Status::kOk);
    }
    std::string why;
    EXPECT_EQ(one_shot_read(d->unix_uri(), why), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(why, "too many clients (64)")) << why;
    const auto t0 = std::chrono::steady_clock::now();
    for (auto& c : idle) {
        objif::Notice notice;
        ASSERT_TRUE(first_notice(*c, notice, 5s));
        EXPECT_EQ(notice.status, objif::Status::kTransportError);
        EXPECT_EQ(notice.text, "idle for 1 s (--idle-timeout 1)");
        EXPECT_TRUE(c->closed_by_peer(5s));
    }
    EXPECT_GE(std::chrono::steady_clock::now() - t0, 500ms) << "closed only once idle";
    EXPECT_EQ(one_shot_read(d->unix_uri(), why), APCI_OK) << why;
    EXPECT_EQ(count_of(d->log(), "idle for 1 s (--idle-timeout 1): connection closed"), 64u)
        << d->log();
}

// A client that keeps talking is never idle; a libapci client that went
// quiet learns why its link is gone at its next request.
TEST(DaemonClients, BusyClientStaysIdleClientLearnsWhyAtItsNextRequest) {
    auto d = start_with({"--idle-timeout", "1"});
    ASSERT_NE(d, nullptr);
    apci_board* busy = nullptr;
    apci_board* quiet = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &busy), APCI_OK);
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &quiet), APCI_OK);
    apci_object_descriptor o{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(2500);
    while (std::chrono::steady_clock::now() < until) {
        ASSERT_EQ(apci_read_int(busy, &o, &n), APCI_OK) << apci_last_error(busy);
        std::this_thread::sleep_for(100ms);
    }
    EXPECT_EQ(apci_read_int(quiet, &o, &n), APCI_TRANSPORT_ERROR);
    const std::string why = apci_last_error(quiet);
    EXPECT_TRUE(contains(why, "daemon " + d->socket_path() +
                                  " closed the connection: idle for 1 s (--idle-timeout 1)"))
        << why;
    EXPECT_EQ(apci_is_connected(quiet), 0);
    EXPECT_EQ(apci_reconnect(quiet), APCI_OK) << apci_last_error(quiet);
    EXPECT_EQ(apci_read_int(quiet, &o, &n), APCI_OK) << apci_last_error(quiet);
    apci_close(busy);
    apci_close(quiet);
}

TEST(DaemonClients, IdleTimeoutZeroNeverClosesAnIdleClient) {
    auto d = start_with({"--idle-timeout", "0"});
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    std::this_thread::sleep_for(2s);
    apci_object_descriptor o{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    EXPECT_EQ(apci_read_int(b, &o, &n), APCI_OK) << apci_last_error(b);
    EXPECT_FALSE(contains(d->log(), "idle")) << d->log();
    apci_close(b);
}

TEST(DaemonClients, IdleTimeoutOutOfRangeIsAUsageError) {
    TempDir dir;
    for (const char* bad : {"-1", "86401", "soon", "1.5"}) {
        std::string out;
        EXPECT_EQ(apci_test::run_daemon({"--socket", dir.file("s"), "--idle-timeout", bad}, out,
                                        dir.path()),
                  2)
            << bad;
        EXPECT_TRUE(contains(out, "--idle-timeout")) << bad << ": " << out;
        EXPECT_FALSE(std::filesystem::exists(dir.file("s"))) << bad;
    }
}

// At shutdown every client is told why its link goes.
TEST(DaemonClients, ClientsAreToldWhenTheDaemonShutsDown) {
    auto d = start_with({});
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    EXPECT_EQ(d->stop(SIGTERM), 0);
    apci_object_descriptor o{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    EXPECT_EQ(apci_read_int(b, &o, &n), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(b), "closed the connection: shutting down (SIGTERM)"))
        << apci_last_error(b);
    apci_close(b);
}

// ---- Point: every terminating signal cleans up

struct SignalCase {
    int signal;  // 0 stands for SIGRTMIN (not a constant expression)
    const char* name;
};

void PrintTo(const SignalCase& c, std::ostream* os) {
    *os << c.name;
}

class DaemonSignals : public ::testing::TestWithParam<SignalCase> {};

bool mailbox_serving(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::uint32_t header[16] = {};
    if (!f.read(reinterpret_cast<char*>(header), sizeof header)) return false;
    return header[objif::mailbox::kOffBoardState / 4] ==
           static_cast<std::uint32_t>(objif::mailbox::BoardState::kServing);
}

// Socket gone, registry entry gone, dual-port RAM file no longer served, the
// signal named in the log, the documented exit code (0 for SIGTERM and
// SIGINT, 128+N otherwise). The test's own check cannot tell a clean exit
// with 128+N from a death by signal N, so the log line and the files tell.
TEST_P(DaemonSignals, EveryTerminatingSignalCleansUpAsSigterm) {
    const SignalCase c = GetParam();
    auto d = start_with({}, true);
    ASSERT_NE(d, nullptr);
    const std::string entry = d->dir().file("rwmos-emu." + std::to_string(d->pid()));
    ASSERT_TRUE(apci_test::eventually([&] { return std::filesystem::exists(entry); }));
    ASSERT_TRUE(mailbox_serving(d->shm_path()));
    const int signal = c.signal == 0 ? SIGRTMIN : c.signal;
    const int expected = signal == SIGTERM || signal == SIGINT ? 0 : 128 + signal;
    EXPECT_EQ(d->stop(signal), expected);
    EXPECT_FALSE(std::filesystem::exists(d->socket_path())) << "socket left behind";
    EXPECT_FALSE(std::filesystem::exists(entry)) << "registry entry left behind";
    EXPECT_FALSE(std::filesystem::exists(d->shm_path()) && mailbox_serving(d->shm_path()))
        << "dual-port RAM file still marked serving";
    EXPECT_TRUE(contains(d->log(), std::string(c.name) + ": shutting down")) << d->log();
    EXPECT_TRUE(contains(d->log(), "stopped: served")) << d->log();
}

INSTANTIATE_TEST_SUITE_P(
    Signals, DaemonSignals,
    ::testing::Values(SignalCase{SIGHUP, "SIGHUP"}, SignalCase{SIGINT, "SIGINT"},
                      SignalCase{SIGQUIT, "SIGQUIT"}, SignalCase{SIGTERM, "SIGTERM"},
                      SignalCase{SIGUSR1, "SIGUSR1"}, SignalCase{SIGUSR2, "SIGUSR2"},
                      SignalCase{SIGALRM, "SIGALRM"}, SignalCase{SIGVTALRM, "SIGVTALRM"},
                      SignalCase{SIGPROF, "SIGPROF"}, SignalCase{SIGXCPU, "SIGXCPU"},
                      SignalCase{SIGXFSZ, "SIGXFSZ"}, SignalCase{SIGPOLL, "SIGPOLL"},
                      SignalCase{SIGPWR, "SIGPWR"}, SignalCase{SIGSTKFLT, "SIGSTKFLT"},
                      SignalCase{0, "SIGRTMIN+0"}),
    [](const ::testing::TestParamInfo<SignalCase>& info) {
        std::string name = info.param.name;
        for (char& ch : name)
            if (ch == '+') ch = '_';
        return name;
    });

TEST(DaemonSignalsPipe, SigpipeIsIgnored) {
    auto d = start_with({});
    ASSERT_NE(d, nullptr);
    ASSERT_EQ(::kill(d->pid(), SIGPIPE), 0);
    std::string why;
    EXPECT_TRUE(
        apci_test::eventually([&] { return one_shot_read(d->unix_uri(), why) == APCI_OK; }, 2s))
        << why;
    std::this_thread::sleep_for(200ms);
    EXPECT_TRUE(d->running());
    EXPECT_EQ(one_shot_read(d->unix_uri(), why), APCI_OK) << why << d->log();
    EXPECT_EQ(d->stop(SIGTERM), 0);
}

// ---- Point: the log counts every Error reply

std::vector<std::uint8_t> frame_of(std::uint16_t opcode, std::uint32_t sequence,
                                   const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> out;
    objif::encode_frame(opcode, sequence, payload, out);
    return out;
}

// Frames whose payload does not decode (a framing-intact frame with a bad
// payload, a bad value tag, a NaN) are answered with an Error reply as much
// as a bad CRC or an unknown opcode: the shutdown line counts them all.
// (It counted only the bad CRC and unknown opcode ones.)
TEST(DaemonLog, ShutdownLineCountsEveryErrorReply) {
    auto d = start_with({});
    ASSERT_NE(d, nullptr);
    RawClient client(d->socket_path());
    std::vector<std::vector<std::uint8_t>> bad;
    bad.push_back(frame_of(0x0001, 1, {1, 2, 3}));  // ObjectRead, short payload
    std::vector<std::uint8_t> tag;
    objif::encode(objif::WriteRequest{objif::Descriptor{{1300, 0, 20, 0}, objif::kNoHandle},
                                      objif::Value::of_double(1.0)},
                  tag);
    std::vector<std::uint8_t> nan = tag;
    tag[20] = 7;  // value tag neither 1 nor 2
    bad.push_back(frame_of(0x0002, 2, tag));
    const double not_a_number = std::numeric_limits<double>::quiet_NaN();
    std::memcpy(nan.data() + 21, &not_a_number, sizeof not_a_number);
    bad.push_back(frame_of(0x0002, 3, nan));
    bad.push_back(frame_of(0x0042, 4, {}));  // unknown opcode
    auto crc = frame_of(0x0001, 5, {});
    crc.back() ^= 0xFF;  // bad CRC
    bad.push_back(crc);
    for (const auto& f : bad) {
        ASSERT_TRUE(client.send(f));
        objif::Frame reply;
        ASSERT_TRUE(client.receive(reply));
        EXPECT_EQ(reply.opcode, 0xFFFF);
    }
    client.close();
    std::string why;
    ASSERT_EQ(one_shot_read(d->unix_uri(), why), APCI_OK) << why;
    EXPECT_EQ(d->stop(SIGTERM), 0);
    EXPECT_TRUE(contains(d->log(), "stopped: served 6 request frames (5 answered with Error)"))
        << d->log();
}

// ---- Point: the socket is bound at its own path

// ss, lsof and /proc/net/unix name a socket by the address it was bound to:
// the daemon's listening socket must be PATH itself, not a staging name.
TEST(DaemonSocketName, ListeningSocketIsBoundAtItsPath) {
    auto d = start_with({});
    ASSERT_NE(d, nullptr);
    std::ifstream f("/proc/net/unix");
    std::string line;
    bool found = false;
    while (std::getline(f, line)) {
        // "Num RefCount Protocol Flags Type St Inode Path"; flags 00010000 = listening.
        std::istringstream fields(line);
        std::string num, refs, protocol, flags, type, state, inode, path;
        fields >> num >> refs >> protocol >> flags >> type >> state >> inode >> path;
        EXPECT_NE(path, d->socket_path() + ".new") << line;
        if (path == d->socket_path() && flags == "00010000") found = true;
    }
    EXPECT_TRUE(found) << "no listening socket bound at " << d->socket_path();
}

// Two daemons started on the same path at the same moment: exactly one
// serves, the other is refused ("live socket of another daemon" or "appeared
// while this daemon was starting"); the socket file is the one that serves.
// (Binding at PATH leaves a moment between bind and listen in which the
// socket refuses connections: the start turn keeps the second daemon
// from taking it for a stale one then.)
TEST(DaemonSocketName, TwoDaemonsStartingTogetherOnOnePathOneServes) {
    for (int round = 0; round < 10; ++round) {
        TempDir dir;
        const std::string path = dir.file("emu.sock");
        pid_t pids[2] = {-1, -1};
        for (pid_t& pid : pids) {
            pid = ::fork();
            ASSERT_GE(pid, 0);
            if (pid == 0) {
                const int null = ::open("/dev/null", O_WRONLY);
                ::dup2(null, 2);
                ::execl(apci_test::daemon_binary(), apci_test::daemon_binary(), "--socket",
                        path.c_str(), nullptr);
                ::_exit(127);
            }
        }
        int refused = -1;
        int status = 0;
        ASSERT_TRUE(apci_test::eventually([&] {
            for (int i = 0; i < 2; ++i)
                if (::waitpid(pids[i], &status, WNOHANG) == pids[i]) refused = i;
            return refused >= 0;
        })) << "round "
            << round << ": neither daemon was refused";
        const pid_t serving = pids[1 - refused];
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << "round " << round;
        apci_board* b = nullptr;
        EXPECT_EQ(apci_open(("unix:" + path).c_str(), &b), APCI_OK)
            << "round " << round << ": " << apci_last_error(nullptr);
        apci_close(b);
        ::kill(serving, SIGTERM);
        ASSERT_EQ(::waitpid(serving, &status, 0), serving);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "round " << round;
        EXPECT_FALSE(std::filesystem::exists(path)) << "round " << round;
    }
}

// Daemons of one user starting in one directory take turns through a lock file in the user's
// registry directory, named after the directory's device and inode. One that holds its turn
// does not make another wait for ever: at most 2 s, then it says what blocks it (exit 1); a
// turn given back within that time is waited for.
TEST(DaemonSocketName, StartTurnHeldByAnotherDaemonIsWaitedForAtMostTwoSeconds) {
    TempDir dir;
    struct stat st {};
    ASSERT_EQ(::stat(dir.path().c_str(), &st), 0);
    const std::string lock_file =
        dir.file(fmt::format("socket-dir.{:x}.{:x}.lock", static_cast<std::uint64_t>(st.st_dev),
                             static_cast<std::uint64_t>(st.st_ino)));
    const Descriptor held(::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600));
    ASSERT_EQ(::flock(held.fd, LOCK_EX), 0);
    std::string out;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(apci_test::run_daemon({"--socket", dir.file("emu.sock")}, out, dir.path()), 1);
    const auto took = std::chrono::steady_clock::now() - t0;
    EXPECT_GE(took, std::chrono::milliseconds(1900));
    EXPECT_LT(took, std::chrono::seconds(6));
    EXPECT_TRUE(contains(out, "another rwmos-emu of this user starting in socket directory " +
                                  dir.path() + " held its turn for 2 s"))
        << out;
    EXPECT_FALSE(std::filesystem::exists(dir.file("emu.sock")));

    std::thread release([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        ::flock(held.fd, LOCK_UN);
    });
    DaemonOptions o;
    o.socket_path = dir.file("emu.sock");
    auto d = Daemon::start(o);
    release.join();
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->stop(), 0);
}

// Anyone may hold flock on a shared directory (/tmp, /dev/shm): that stopped every daemon from
// starting there. The socket directory's own lock means nothing to the daemon now; here it is
// held by another user (nobody) on a shared directory while the daemon starts there.
TEST(DaemonSocketName, AFlockOnTheSocketDirectoryByAnotherUserDoesNotStopTheDaemon) {
    TempDir dir;
    TempDir shared;
    ASSERT_EQ(::chmod(shared.path().c_str(), 01777), 0);
    // Close-on-exec: the daemon started below must not keep `done` open for the holder.
    int ready[2], done[2];
    ASSERT_EQ(::pipe2(ready, O_CLOEXEC), 0);
    ASSERT_EQ(::pipe2(done, O_CLOEXEC), 0);
    const pid_t holder = ::fork();
    ASSERT_GE(holder, 0);
    if (holder == 0) {
        ::close(ready[0]);
        ::close(done[1]);
        if (test_support::can_act_as_other_user() &&
            (::setgroups(0, nullptr) != 0 ||
             ::setresgid(test_support::kOtherGid, test_support::kOtherGid,
                         test_support::kOtherGid) != 0 ||
             ::setresuid(test_support::kOtherUid, test_support::kOtherUid,
                         test_support::kOtherUid) != 0))
            ::_exit(3);
        const int fd = ::open(shared.path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        const char ok = fd >= 0 && ::flock(fd, LOCK_EX) == 0 ? 'y' : 'n';
        (void)!::write(ready[1], &ok, 1);
        char c = 0;
        (void)!::read(done[0], &c, 1);  // hold it until the test is done
        ::_exit(0);
    }
    ::close(ready[1]);
    ::close(done[0]);
    char ok = 0;
    ASSERT_EQ(::read(ready[0], &ok, 1), 1);
    EXPECT_EQ(ok, 'y');
    DaemonOptions o;
    o.socket_path = shared.file("emu.sock");
    auto d = Daemon::start(o);
    ::close(done[1]);
    ::close(ready[0]);
    int status = 0;
    ::waitpid(holder, &status, 0);
    ASSERT_NE(d, nullptr);
    EXPECT_FALSE(contains(d->log(), "held its turn")) << d->log();
    EXPECT_EQ(d->stop(), 0);
}

// ---- Point: apcictl list names only rwmos-emu daemons as daemons

TEST(DaemonList, ListenerThatIsNotADaemonIsListedAsNotOne) {
    TempDir dir;
    // Something else listening where a registry entry says a daemon is.
    const std::string path = dir.file("other.sock");
    const Descriptor listener(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    ASSERT_EQ(::bind(listener.fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    ASSERT_EQ(::listen(listener.fd, 4), 0);
    std::ofstream(dir.file("rwmos-emu." + std::to_string(::getpid()))) << "socket " << path << "\n";
    // And a real daemon next to it.
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    // The daemon registers itself once it serves (after its socket appears): wait for the entry.
    const std::string entry = d->dir().file("rwmos-emu." + std::to_string(d->pid()));
    ASSERT_TRUE(apci_test::eventually([&] { return std::filesystem::exists(entry); }));
    std::filesystem::copy_file(entry, dir.file("rwmos-emu." + std::to_string(d->pid())));
    const auto r =
        test_support::run_process({APCICTL_PATH, "list"}, {}, {{"APCI_RUNTIME_DIR", dir.path()}});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::string daemon_line, other_line;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
        if (line.starts_with("unix:" + d->socket_path() + " ")) daemon_line = line;
        if (line.starts_with("unix:" + path + " ")) other_line = line;
    }
    EXPECT_TRUE(daemon_line.ends_with("  rwmos-emu daemon, pid " + std::to_string(d->pid())))
        << r.out;
    EXPECT_TRUE(other_line.ends_with("  not an rwmos-emu daemon (registered by pid " +
                                     std::to_string(::getpid()) + "; no greeting within 500 ms)"))
        << r.out;
}

// `apcictl list` while a daemon started in `dir` (its runtime directory and working directory)
// with `args` is registered; the daemon (its pid in `pid`) is stopped before the answer is
// returned.
test_support::ProcessResult listed_with_daemon(const TempDir& dir,
                                               const std::vector<std::string>& args, pid_t& pid) {
    pid = ::fork();
    if (pid < 0) return {};
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 2);
        if (::chdir(dir.path().c_str()) != 0) ::_exit(126);
        ::setenv("APCI_RUNTIME_DIR", dir.path().c_str(), 1);
        std::vector<char*> argv{const_cast<char*>(apci_test::daemon_binary())};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(apci_test::daemon_binary(), argv.data());
        ::_exit(127);
    }
    const std::string entry = dir.file("rwmos-emu." + std::to_string(pid));
    EXPECT_TRUE(apci_test::eventually([&] { return std::filesystem::exists(entry); }));
    auto r =
        test_support::run_process({APCICTL_PATH, "list"}, {}, {{"APCI_RUNTIME_DIR", dir.path()}});
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return r;
}

// A daemon started with relative paths registers them absolute: `apcictl list` run from
// another directory prints URIs that open the board (it printed "unix:emu.sock").
TEST(DaemonList, RelativePathsAreRegisteredAbsolute) {
    TempDir dir;
    pid_t pid = 0;
    const auto r = listed_with_daemon(dir, {"--socket", "emu.sock", "--shm", "./emu.dpram"}, pid);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(
        r.out, "unix:" + dir.file("emu.sock") + "  rwmos-emu daemon, pid " + std::to_string(pid)))
        << r.out;
    EXPECT_TRUE(contains(r.out, "shm:" + dir.file("emu.dpram") + " ")) << r.out;
}

// A socket path with a line end and "shm FILE" after it: the registry keeps it whole, and
// `apcictl list` prints it escaped on the board's one line (it printed a second line,
// "shm precious.txt  rwmos-emu daemon, pid N").
TEST(DaemonList, ASocketPathWithALineEndIsListedOnOneLine) {
    TempDir dir;
    pid_t pid = 0;
    const auto r = listed_with_daemon(dir, {"--socket", dir.file("x\nshm precious.txt")}, pid);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, "unix:" + dir.file("x\\nshm precious.txt") + "  rwmos-emu daemon, pid " +
                         std::to_string(pid) + "\n");
}

}  // namespace
