// SPDX-License-Identifier: MIT
// rwmos-emu, the emulator daemon: its command line, its socket's life cycle,
// and its robustness against clients (docs/rwmos-emu.md, docs/hardening.md):
// malformed frames of every class and clients that vanish mid-frame leave it
// serving with the board state unchanged; concurrent clients' writes are
// neither lost nor duplicated.
#include "daemon.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.h"
#include "objif/frame.h"
#include "raw_client.h"
#include "text.h"

namespace {

using test_support::count_of;
using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::TempDir;
using daemon_test::RawClient;
using objif::FrameError;
using objif::Opcode;
using objif::Status;

constexpr objif::Address kRotAngle{1300, 0, 20, 0};

// Every readable object a PCAP program can see, as text: the board state.
std::vector<std::string> board_state(const std::string& uri) {
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open(uri.c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    std::vector<apci_object_descriptor> objects;
    for (int i = 1; i <= 7; ++i) objects.push_back({1000, 0, i, 0, 0});
    for (int axis = 0; axis < 8; ++axis) objects.push_back({1000, 0, 10, axis, 0});
    for (int sub = 0; sub < 3; ++sub) objects.push_back({1300, 0, 11, sub, 0});
    for (int index : {12, 20, 21, 22}) objects.push_back({1300, 0, index, 0, 0});
    for (int g = 0; g <= 3; ++g)
        for (int sub : {1, 3, 4, 5, 7, 8, 11, 12, 20, 21}) objects.push_back({1300, 1, g, sub, 0});
    std::vector<std::string> state;
    for (auto& o : objects) {
        std::int32_t i = 0;
        double d = 0;
        apci_status s = apci_read_int(b, &o, &i);
        if (s == APCI_OK) {
            state.push_back(
                fmt::format("{}/{}/{}/{} = {}", o.bus, o.device, o.index, o.subindex, i));
            continue;
        }
        o.handle = 0;
        s = apci_read_double(b, &o, &d);
        state.push_back(
            s == APCI_OK ? fmt::format("{}/{}/{}/{} = {}", o.bus, o.device, o.index, o.subindex, d)
                         : fmt::format("{}/{}/{}/{}: {}", o.bus, o.device, o.index, o.subindex,
                                       apci_status_name(s)));
    }
    apci_close(b);
    return state;
}

// The board at `uri` answers a read of AxisCount.
bool serves(const std::string& uri) {
    apci_board* b = nullptr;
    if (apci_open(uri.c_str(), &b) != APCI_OK) return false;
    apci_object_descriptor o{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    const bool ok = apci_read_int(b, &o, &n) == APCI_OK && n == 8;
    apci_close(b);
    return ok;
}

// ---- Command line

TEST(DaemonCommandLine, HelpNamesEveryOptionAndExitsZero) {
    TempDir dir;
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--help"}, out, dir.path()), 0);
    for (const char* option :
         {"--socket", "--shm", "--realtime", "--no-option-tc", "--max-clients", "--log-level"})
        EXPECT_NE(out.find(option), std::string::npos) << option << " missing from:\n" << out;
}

TEST(DaemonCommandLine, NoSocketAndNoShmIsAUsageError) {
    TempDir dir;
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({}, out, dir.path()), 2);
    EXPECT_NE(out.find("--socket"), std::string::npos) << out;
}

TEST(DaemonCommandLine, UnknownOptionIsAUsageError) {
    TempDir dir;
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--socket", dir.file("s"), "--frobnicate"}, out, dir.path()),
              2);
}

TEST(DaemonCommandLine, BadLogLevelIsAUsageError) {
    TempDir dir;
    std::string out;
    EXPECT_EQ(
        apci_test::run_daemon({"--socket", dir.file("s"), "--log-level", "loud"}, out, dir.path()),
        2);
}

// ---- Socket life cycle

TEST(DaemonSocket, IsCreatedWithMode0660) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    struct stat st {};
    ASSERT_EQ(::stat(d->socket_path().c_str(), &st), 0);
    EXPECT_TRUE(S_ISSOCK(st.st_mode));
    EXPECT_EQ(st.st_mode & 0777, 0660u);
}

TEST(DaemonSocket, ShmFileIsCreatedWithMode0660) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    struct stat st {};
    ASSERT_EQ(::stat(d->shm_path().c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0660u);
}

TEST(DaemonSocket, SigtermRemovesSocketAndShmFileAndExitsZero) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->stop(SIGTERM), 0) << d->log();
    EXPECT_FALSE(std::filesystem::exists(d->socket_path()));
    EXPECT_FALSE(std::filesystem::exists(d->shm_path()));
    EXPECT_NE(d->log().find("SIGTERM: shutting down"), std::string::npos) << d->log();
}

TEST(DaemonSocket, SigintRemovesSocketAndExitsZero) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->stop(SIGINT), 0) << d->log();
    EXPECT_FALSE(std::filesystem::exists(d->socket_path()));
}

TEST(DaemonSocket, ShutdownWithClientsConnectedIsClean) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    RawClient a(d->socket_path()), b(d->socket_path());
    ASSERT_TRUE(a.connected() && b.connected());
    EXPECT_EQ(d->stop(SIGTERM), 0) << d->log();
    EXPECT_TRUE(a.closed_by_peer());
    EXPECT_FALSE(std::filesystem::exists(d->socket_path()));
}

TEST(DaemonSocket, StaleSocketIsRemovedAndServed) {
    TempDir dir;
    const std::string path = dir.file("stale.sock");
    {  // A socket file nobody listens on: what a killed daemon leaves behind.
        const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
        ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
        ::close(fd);
    }
    DaemonOptions o;
    o.socket_path = path;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    EXPECT_TRUE(apci_test::eventually([&] { return RawClient(path).connected(); }));
    EXPECT_NE(d->log().find("removed stale socket"), std::string::npos) << d->log();
    EXPECT_EQ(d->stop(), 0);
}

TEST(DaemonSocket, LiveSocketOfAnotherDaemonIsRefused) {
    auto first = Daemon::start();
    ASSERT_NE(first, nullptr);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--socket", first->socket_path()}, out, first->dir().path()),
              1);
    EXPECT_NE(out.find("live socket of another daemon"), std::string::npos) << out;
    EXPECT_TRUE(serves(first->unix_uri())) << "the first daemon still serves";
}

TEST(DaemonSocket, PathThatIsNotASocketIsRefusedAndKept) {
    TempDir dir;
    const std::string path = dir.file("precious.txt");
    std::ofstream(path) << "keep me\n";
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--socket", path}, out, dir.path()), 1);
    EXPECT_NE(out.find("is not a socket"), std::string::npos) << out;
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);
    EXPECT_EQ(line, "keep me");
}

// A client (or a script, or a service manager) that waits for the socket file
// to appear can open it the moment it sees it: the daemon binds the socket at
// its path and listens right after, and libapci retries a connect refused in
// between (a few microseconds) for 10 ms. Checked with a client that polls
// without sleeping, over several starts.
TEST(DaemonSocket, SocketFileCanBeOpenedTheMomentItAppears) {
    for (int start = 0; start < 20; ++start) {
        TempDir dir;
        const std::string path = dir.file("emu.sock");
        const pid_t pid = ::fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            const int null = ::open("/dev/null", O_WRONLY);
            ::dup2(null, 2);
            ::execl(apci_test::daemon_binary(), apci_test::daemon_binary(), "--socket",
                    path.c_str(), nullptr);
            ::_exit(127);
        }
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (!std::filesystem::exists(path) && std::chrono::steady_clock::now() < deadline) {
        }
        const bool appeared = std::filesystem::exists(path);
        apci_board* b = nullptr;
        const bool opened = appeared && apci_open(("unix:" + path).c_str(), &b) == APCI_OK;
        const std::string why = apci_last_error(nullptr);
        apci_close(b);
        ::kill(pid, SIGTERM);
        ::waitpid(pid, nullptr, 0);
        ASSERT_TRUE(appeared) << "start " << start;
        ASSERT_TRUE(opened) << "start " << start << ": " << why;
    }
}

// The socket is bound at PATH itself (no staging name): a file next to it,
// such as PATH.new, is not touched.
TEST(DaemonSocket, NoOtherNameNextToThePathIsTouched) {
    TempDir dir;
    const std::string path = dir.file("emu.sock");
    std::ofstream(path + ".new") << "keep me\n";
    DaemonOptions o;
    o.socket_path = path;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    EXPECT_TRUE(serves(d->unix_uri()));
    EXPECT_EQ(d->stop(), 0);
    std::ifstream f(path + ".new");
    std::string line;
    std::getline(f, line);
    EXPECT_EQ(line, "keep me");
}

TEST(DaemonSocket, PathTooLongIsRefusedWithTheLimit) {
    TempDir dir;
    std::string path = dir.path() + "/";
    path += std::string(sizeof(sockaddr_un::sun_path) - path.size(), 's');  // one byte too many
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--socket", path}, out, dir.path()), 1);
    EXPECT_NE(out.find("is too long (at most 107 bytes"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(DaemonSocket, SecondDaemonOnTheSameShmFileIsRefused) {
    DaemonOptions o;
    o.socket = false;
    o.shm = true;
    auto first = Daemon::start(o);
    ASSERT_NE(first, nullptr);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--shm", first->shm_path()}, out, first->dir().path()), 1);
    EXPECT_NE(out.find("served by another daemon"), std::string::npos) << out;
}

TEST(DaemonSocket, ClientsBeyondMaxClientsAreRefusedOthersKeepWorking) {
    DaemonOptions o;
    o.extra_args = {"--max-clients", "2"};
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    // The fixture's readiness probe may still count as a client for a moment:
    // open each board until it is served.
    auto open_served = [&](apci_board*& b) {
        return apci_test::eventually([&] {
            apci_close(b);
            b = nullptr;
            if (apci_open(d->unix_uri().c_str(), &b) != APCI_OK) return false;
            apci_object_descriptor o{1000, 0, 3, 0, 0};
            std::int32_t n = 0;
            return apci_read_int(b, &o, &n) == APCI_OK;
        });
    };
    apci_board* a = nullptr;
    apci_board* b = nullptr;
    ASSERT_TRUE(open_served(a));
    ASSERT_TRUE(open_served(b));
    RawClient third(d->socket_path());
    EXPECT_TRUE(third.closed_by_peer()) << d->log();
    apci_object_descriptor o1{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    EXPECT_EQ(apci_read_int(a, &o1, &n), APCI_OK);
    EXPECT_EQ(apci_read_int(b, &o1, &n), APCI_OK);
    EXPECT_NE(d->log().find("refused a client: 2 clients connected"), std::string::npos)
        << d->log();
    apci_close(a);
    apci_close(b);
}

TEST(DaemonSocket, OptionNoOptionTcRemovesTheTcModule) {
    DaemonOptions o;
    o.option_tc = false;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    apci_object_descriptor plane{1300, 0, 12, 0, 0};
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &plane, &v), APCI_NO_SUCH_DEVICE);
    apci_close(b);
}

// ---- Time

std::uint64_t board_cycles(apci_board* b) {
    apci_motion_status st{};
    EXPECT_EQ(apci_motion_status_get(b, &st), APCI_OK) << apci_last_error(b);
    return st.now;
}

TEST(DaemonTime, WithoutRealtimeTheClockRunsOnlyWhenAClientStepsIt) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    const std::uint64_t before = board_cycles(b);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    EXPECT_EQ(board_cycles(b), before);
    ASSERT_EQ(apci_step(b, 7, nullptr), APCI_OK);
    EXPECT_EQ(board_cycles(b), before + 7);
    apci_close(b);
}

TEST(DaemonTime, RealtimePacesTheClockToWallTime) {
    DaemonOptions o;
    o.extra_args = {"--realtime"};
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    EXPECT_TRUE(apci_test::eventually([&] { return d->log().find("wall time") != std::string::npos; }))
        << d->log();
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    const auto t0 = std::chrono::steady_clock::now();
    const std::uint64_t c0 = board_cycles(b);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const std::uint64_t c1 = board_cycles(b);
    const auto wall_ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0)
            .count();
    // One cycle per millisecond (InterpolationCycle 1000 us); the pacer may lag by a few ticks.
    EXPECT_LE(c1 - c0, static_cast<std::uint64_t>(wall_ms) + 2);
    EXPECT_GE(c1 - c0, static_cast<std::uint64_t>(wall_ms) * 8 / 10) << "wall " << wall_ms << " ms";
    apci_close(b);
}

TEST(DaemonTime, RealtimeMovesTheAxesAtTheProgrammedFeed) {
    DaemonOptions o;
    o.extra_args = {"--realtime"};
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    apci_profile p{};
    p.kind = APCI_PROFILE_LINE;
    p.axes = 0x01;
    p.feed = 6000.0;  // 100 units a second
    p.target[0] = 1000.0;
    ASSERT_EQ(apci_spool_profile(b, &p, nullptr), APCI_OK) << apci_last_error(b);
    const auto t0 = std::chrono::steady_clock::now();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    apci_motion_status st{};
    ASSERT_EQ(apci_motion_status_get(b, &st), APCI_OK);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GT(st.position[0], 0.0) << "the axis moves without any client stepping the clock";
    EXPECT_LE(st.position[0], 100.0 * seconds + 1.0);
    EXPECT_GE(st.position[0], 100.0 * seconds * 0.7);
    apci_close(b);
}

// ---- Robustness

struct MalformedClass {
    const char* name;
    // Makes the bad frame from a good ObjectWrite frame (RotAngle = 7.5).
    std::vector<std::uint8_t> (*make)(std::uint32_t sequence);
    bool drops;     // garbage: the connection is dropped
    Status status;  // else: the Error reply's status
};

std::vector<std::uint8_t> good_write(std::uint32_t seq) {
    return daemon_test::write_double_frame(seq, kRotAngle, 7.5);
}

void put_u16(std::vector<std::uint8_t>& f, std::size_t at, std::uint16_t v) {
    std::memcpy(f.data() + at, &v, 2);
}
void put_u32(std::vector<std::uint8_t>& f, std::size_t at, std::uint32_t v) {
    std::memcpy(f.data() + at, &v, 4);
}

// Re-frames `payload` under `op` with a correct CRC.
std::vector<std::uint8_t> reframed(std::uint16_t op, std::uint32_t seq,
                                   std::vector<std::uint8_t> payload) {
    std::vector<std::uint8_t> out;
    objif::encode_frame(op, seq, payload, out);
    return out;
}
std::vector<std::uint8_t> write_payload() {
    std::vector<std::uint8_t> f = good_write(0);
    return {f.begin() + objif::kFrameHeaderSize, f.end() - objif::kFrameCrcSize};
}

const MalformedClass kMalformed[] = {
    {"BadMagic",
     [](std::uint32_t s) {
         auto f = good_write(s);
         f[0] ^= 0xFF;
         return f;
     },
     true, Status::kOk},
    {"BadVersion",
     [](std::uint32_t s) {
         auto f = good_write(s);
         put_u16(f, 4, objif::kFrameVersion - 1);  // 0.1.0's client
         return f;
     },
     true, Status::kOk},
    {"BadLength",
     [](std::uint32_t s) {
         auto f = good_write(s);
         put_u32(f, 12, objif::kMaxPayload + 1);
         return f;
     },
     true, Status::kOk},
    {"BadCrc",
     [](std::uint32_t s) {
         auto f = good_write(s);
         f[objif::kFrameHeaderSize + 21] ^= 0x01;
         return f;
     },
     false, Status::kBadFrame},
    {"UnknownOpcode", [](std::uint32_t s) { return reframed(0x0042, s, write_payload()); }, false,
     Status::kUnknownOpcode},
    {"ReplyOpcodeAsRequest", [](std::uint32_t s) { return reframed(0x8002, s, write_payload()); },
     false, Status::kUnknownOpcode},
    {"BadPayload",
     [](std::uint32_t s) {
         auto p = write_payload();
         p.pop_back();
         return reframed(0x0002, s, p);
     },
     false, Status::kBadFrame},
    {"BadValueTag",
     [](std::uint32_t s) {
         auto p = write_payload();
         p[20] = 7;
         return reframed(0x0002, s, p);
     },
     false, Status::kTypeMismatch},
    {"NotFinite",
     [](std::uint32_t s) {
         return daemon_test::write_double_frame(s, kRotAngle,
                                                std::numeric_limits<double>::quiet_NaN());
     },
     false, Status::kInvalidValue},
};

class DaemonMalformed : public ::testing::TestWithParam<MalformedClass> {};

TEST_P(DaemonMalformed, ThousandFramesLeaveItServingWithBoardStateUnchanged) {
    const MalformedClass& c = GetParam();
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    const auto before = board_state(d->unix_uri());
    constexpr std::uint32_t kFrames = 1000;
    if (c.drops) {
        for (std::uint32_t i = 1; i <= kFrames; ++i) {
            RawClient client(d->socket_path());
            ASSERT_TRUE(client.send(c.make(i)));
            ASSERT_TRUE(client.closed_by_peer())
                << c.name << " frame " << i << " did not drop the connection";
        }
    } else {
        RawClient client(d->socket_path());
        for (std::uint32_t i = 1; i <= kFrames; ++i) {
            ASSERT_TRUE(client.send(c.make(i)));
            objif::Frame reply;
            ASSERT_TRUE(client.receive(reply)) << c.name << " frame " << i << " got no reply";
            ASSERT_EQ(reply.opcode, 0xFFFF) << "an Error reply";
            ASSERT_EQ(reply.sequence, i) << "the Error reply echoes the sequence";
            objif::ErrorReply error;
            ASSERT_EQ(objif::decode(reply.payload, error), FrameError::kNone);
            ASSERT_EQ(error.status, c.status) << objif::status_name(error.status);
        }
        // The same connection goes on serving good frames.
        ASSERT_TRUE(
            client.send(daemon_test::write_double_frame(kFrames + 1, {1300, 0, 21, 0}, 1.0)));
        objif::Frame reply;
        ASSERT_TRUE(client.receive(reply));
        EXPECT_EQ(reply.opcode, 0x8002);
        ASSERT_TRUE(
            client.send(daemon_test::write_double_frame(kFrames + 2, {1300, 0, 21, 0}, 0.0)));
        ASSERT_TRUE(client.receive(reply));
    }
    EXPECT_EQ(board_state(d->unix_uri()), before);
    EXPECT_EQ(d->stop(), 0) << d->log();
}

INSTANTIATE_TEST_SUITE_P(EveryClass, DaemonMalformed, ::testing::ValuesIn(kMalformed),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(DaemonRobustness, HundredClientsDisconnectingMidFrameLeaveItServingWithBoardStateUnchanged) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    const auto before = board_state(d->unix_uri());
    const auto frame = good_write(1);
    for (int i = 0; i < 100; ++i) {
        RawClient client(d->socket_path());
        // Cut at a different place each time: inside the header, the payload, the CRC.
        const std::size_t cut = 1 + static_cast<std::size_t>(i) % (frame.size() - 1);
        ASSERT_TRUE(client.send(std::span(frame).first(cut)));
        client.close();
        // Each vanished client is noticed (and forgotten) before the next comes.
        ASSERT_TRUE(apci_test::eventually([&] {
            return count_of(d->log(), "disconnected mid-frame") == static_cast<std::size_t>(i) + 1;
        })) << d->log();
    }
    EXPECT_EQ(board_state(d->unix_uri()), before);
    EXPECT_EQ(d->stop(), 0);
}

TEST(DaemonRobustness, ClientThatDoesNotReadItsRepliesDoesNotStallOthers) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    RawClient lazy(d->socket_path());
    // Far more replies than the socket buffers hold, never read.
    std::vector<std::uint8_t> burst;
    for (std::uint32_t i = 1; i <= 20000; ++i) {
        auto f = daemon_test::write_double_frame(i, kRotAngle, 1.0);
        burst.insert(burst.end(), f.begin(), f.end());
    }
    std::thread writer([&] { lazy.send(burst); });  // blocks once the daemon stops reading it
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
    apci_object_descriptor o{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    for (int i = 0; i < 100; ++i)
        ASSERT_EQ(apci_read_int(b, &o, &n), APCI_OK) << apci_last_error(b);
    apci_close(b);
    lazy.shutdown();  // unblocks the writer
    writer.join();
    lazy.close();
    EXPECT_EQ(d->stop(), 0);
}

// One client advancing a long, sampled stretch of time (each cycle computed)
// does not hold the board for the others: the board takes at most 2^20
// cycles per Clock request and libapci splits longer steps, so the daemon
// serves other clients in between. The other client sees the clock part of
// the way through, which it could not if the step were served as one request.
TEST(DaemonRobustness, LongSampledStepOfOneClientLetsOthersBeServedMeanwhile) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    apci_board* stepper = nullptr;
    apci_board* other = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &stepper), APCI_OK);
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &other), APCI_OK);
    // Each request of the step computes 2^20 cycles: well under a second here,
    // but several under the sanitizers on a loaded machine. What is checked is
    // the order in which the two clients are served, not how fast.
    ASSERT_EQ(apci_set_timeout(stepper, 120'000), APCI_OK);
    ASSERT_EQ(apci_set_timeout(other, 120'000), APCI_OK);
    ASSERT_EQ(apci_trace_enable(stepper, 1024), APCI_OK) << apci_last_error(stepper);
    constexpr std::uint64_t kCycles = 4 * objif::kMaxClockCycles;
    std::atomic<bool> stepped{false};
    apci_status step_status = APCI_OK;
    apci_motion_status after{};
    std::thread t([&] {
        step_status = apci_step(stepper, kCycles, &after);
        stepped = true;
    });
    std::uint64_t seen_midway = 0;
    std::size_t served = 0;
    while (!stepped) {
        apci_motion_status st{};
        ASSERT_EQ(apci_motion_status_get(other, &st), APCI_OK) << apci_last_error(other);
        ++served;
        if (st.now > 0 && st.now < kCycles) seen_midway = st.now;
    }
    t.join();
    ASSERT_EQ(step_status, APCI_OK) << apci_last_error(stepper);
    EXPECT_EQ(after.ran, kCycles);
    EXPECT_EQ(after.now, kCycles);
    EXPECT_NE(seen_midway, 0u) << "the other client was served only before or after the step ("
                               << served << " requests)";
    apci_close(other);
    apci_close(stepper);
    EXPECT_EQ(d->stop(), 0);
}

// 16 clients, each with an object of its own, 10,000 writes each; every
// write is read back at once, so a lost write shows as the old value and a
// duplicated (replayed) one as a value the client wrote earlier. The daemon
// counts the frames it served: exactly the requests sent, none twice.
TEST(DaemonRobustness, SixteenConcurrentClientsTenThousandWritesEachNoneLostNoneDuplicated) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    struct Owned {
        apci_object_descriptor object;
        bool is_double;
    };
    std::vector<Owned> owned = {
        {{1300, 0, 20, 0, 0}, true}, {{1300, 0, 21, 0, 0}, true}, {{1300, 0, 22, 0, 0}, true},
        {{1300, 1, 1, 7, 0}, true},  {{1300, 1, 2, 7, 0}, true},  {{1300, 1, 3, 7, 0}, true},
        {{1300, 1, 1, 12, 0}, true}, {{1300, 1, 2, 12, 0}, true}, {{1300, 1, 3, 12, 0}, true},
        {{1000, 0, 4, 0, 0}, false}, {{1300, 1, 1, 4, 0}, false}, {{1300, 1, 2, 4, 0}, false},
        {{1300, 1, 3, 4, 0}, false}, {{1300, 1, 1, 5, 0}, false}, {{1300, 1, 2, 5, 0}, false},
        {{1300, 1, 3, 5, 0}, false},
    };
    ASSERT_EQ(owned.size(), 16u);
    constexpr int kWrites = 10000;
    std::atomic<int> failures{0};
    std::vector<std::string> first_failure(owned.size());
    std::vector<std::thread> clients;
    for (std::size_t k = 0; k < owned.size(); ++k) {
        clients.emplace_back([&, k] {
            apci_board* b = nullptr;
            if (apci_open(d->unix_uri().c_str(), &b) != APCI_OK) {
                ++failures;
                first_failure[k] = apci_last_error(nullptr);
                return;
            }
            apci_object_descriptor o = owned[k].object;
            for (int i = 0; i < kWrites; ++i) {
                bool same = false;
                if (owned[k].is_double) {
                    const double v = static_cast<double>(k) * 20000.0 + i + 0.25;
                    double back = 0;
                    same = apci_write_double(b, &o, v) == APCI_OK &&
                           apci_read_double(b, &o, &back) == APCI_OK && back == v;
                } else {
                    // Consecutive values differ; InterpolationCycle stays in 250..10000.
                    const std::int32_t v = o.bus == 1000 ? 250 + i % 9751 : i % 8;
                    std::int32_t back = -1;
                    same = apci_write_int(b, &o, v) == APCI_OK &&
                           apci_read_int(b, &o, &back) == APCI_OK && back == v;
                }
                if (!same) {
                    if (failures++ == 0 || first_failure[k].empty())
                        first_failure[k] = fmt::format("write {}: {}", i, apci_last_error(b));
                    break;
                }
            }
            apci_close(b);
        });
    }
    for (auto& t : clients) t.join();
    EXPECT_EQ(failures.load(), 0) << fmt::format("{}", fmt::join(first_failure, "\n"));
    ASSERT_EQ(d->stop(), 0);
    std::smatch m;
    const std::string log = d->log();
    ASSERT_TRUE(
        std::regex_search(log, m, std::regex("served (\\d+) request frames \\((\\d+) answered")))
        << log;
    EXPECT_EQ(std::stoull(m[1]), 16ull * kWrites * 2) << "every request served exactly once";
    EXPECT_EQ(std::stoull(m[2]), 0ull);
}

}  // namespace
