// SPDX-License-Identifier: MIT
// What one client cannot take from the others: the board's time (its requests are served in
// turns), the daemon's memory (a trace within --trace-memory, replies it does not read within
// kMaxQueuedReplies), and the daemon's descriptors (out of them, a newcomer is told why and
// the daemon does not spin). docs/hardening.md, "Resource limits".
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.h"
#include "daemon.h"
#include "objif/frame.h"
#include "raw_client.h"
#include "text.h"

namespace {

using test_support::contains;
using test_support::count_of;
using apci_test::Daemon;
using apci_test::DaemonOptions;
using daemon_test::RawClient;
using namespace std::chrono_literals;

std::vector<std::uint8_t> clock_frame(std::uint32_t sequence, objif::ClockMode mode,
                                      std::uint64_t cycles) {
    std::vector<std::uint8_t> payload;
    objif::encode(objif::ClockRequest{mode, cycles}, payload);
    return daemon_test::frame_bytes(objif::Opcode::kClock, sequence, payload);
}

std::vector<std::uint8_t> trace_frame(std::uint32_t sequence, std::uint32_t max) {
    std::vector<std::uint8_t> payload;
    objif::encode(objif::TraceRequest{objif::TraceKind::kSamples, max}, payload);
    return daemon_test::frame_bytes(objif::Opcode::kReadTrace, sequence, payload);
}

// What process `pid`'s descriptors refer to, "N:target" each, for a failure's message.
std::string descriptors_of(pid_t pid) {
    std::string out;
    std::error_code ec;
    const std::filesystem::path dir = "/proc/" + std::to_string(pid) + "/fd";
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        std::error_code link_ec;
        const auto target = std::filesystem::read_symlink(entry.path(), link_ec);
        out += entry.path().filename().string() + ":" + target.string() + " ";
    }
    return out;
}

// The Clock reply in `frame`, or a test failure.
objif::ClockReply clock_reply(const objif::Frame& frame) {
    objif::ClockReply reply;
    EXPECT_EQ(objif::decode(frame.payload, reply), objif::FrameError::kNone);
    return reply;
}

// The board's clock and trace as another client sees them now.
apci_motion_status status_of(const std::string& uri) {
    apci_board* b = nullptr;
    apci_motion_status st{};
    // The link's timeout from the start: it also bounds the wait for the daemon's greeting,
    // which comes between two of the other client's turns; one turn (a whole step) takes
    // seconds under ThreadSanitizer on a loaded machine (the default 2000 ms ran out there).
    const std::string patient = uri + "?timeout=60000";
    EXPECT_EQ(apci_open(patient.c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    if (b == nullptr) return st;
    EXPECT_EQ(apci_motion_status_get(b, &st), APCI_OK) << apci_last_error(b);
    apci_close(b);
    return st;
}

// ---- Work per turn

// A client that writes hundreds of long sampled Clock steps in one write does not hold the
// board until they are all done (it held it for 28 to 55 s): between two of its requests the
// daemon greets a newcomer, serves another socket client and the dual-port RAM thread. What is
// checked is the order (the others see the board's clock part way through the steps), not
// how fast.
TEST(DaemonFairness, PipelinedStepsOfOneClientLetEveryOtherClientInBetween) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    RawClient stepper(d->socket_path());
    ASSERT_TRUE(stepper.send(clock_frame(1, objif::ClockMode::kTraceOn, 1024)));
    objif::Frame frame;
    ASSERT_TRUE(stepper.receive(frame));
    ASSERT_EQ(clock_reply(frame).status, objif::Status::kOk);
    // Every cycle computed (the trace is on): each step 30 to 45 ms here, far more under the
    // sanitizers; all of them together would take minutes.
    constexpr std::uint32_t kSteps = 400;
    std::vector<std::uint8_t> steps;
    for (std::uint32_t i = 0; i < kSteps; ++i) {
        const auto f = clock_frame(2 + i, objif::ClockMode::kStep, objif::kMaxClockCycles);
        steps.insert(steps.end(), f.begin(), f.end());
    }
    ASSERT_TRUE(stepper.send(steps));           // one write
    ASSERT_TRUE(stepper.receive(frame, 120s));  // the first step has run
    ASSERT_EQ(frame.sequence, 2u);
    constexpr std::uint64_t kAll = std::uint64_t{kSteps} * objif::kMaxClockCycles;

    // A newcomer is greeted and served while the steps go on.
    RawClient newcomer(d->socket_path());
    ASSERT_TRUE(newcomer.send(clock_frame(7, objif::ClockMode::kQuery, 0)));
    ASSERT_TRUE(newcomer.receive(frame, 60s)) << "the newcomer waited for the other's steps";
    const objif::ClockReply seen = clock_reply(frame);
    EXPECT_GT(seen.now, 0u);
    EXPECT_LT(seen.now, kAll) << "served only after every step";
    // So is a libapci client on the socket, and one on the dual-port RAM file.
    EXPECT_LT(status_of(d->unix_uri()).now, kAll);
    const apci_motion_status through_shm = status_of(d->shm_uri());
    EXPECT_GT(through_shm.now, 0u);
    EXPECT_LT(through_shm.now, kAll) << "the dual-port RAM thread waited for the steps";
    stepper.close();
    EXPECT_EQ(d->stop(), 0);  // between two turns, not after the steps
}

// ---- Memory per client

// The trace's ring is the board's one large store, and its memory grows with what waits
// unread (2^24 samples and a few steps took 1.2 GB; under a memory limit std::bad_alloc ended
// the daemon). A daemon gives it at most --trace-memory (64 MiB by default): a ring of 932,067
// samples (72 bytes each) fits, one more is refused with NoMemory and a reason, and nothing
// changes; --trace-memory 1 allows 14,563.
TEST(DaemonMemory, ATraceLargerThanTheTraceMemoryIsRefusedWithAReason) {
    for (const auto& [args, fits] :
         {std::pair<std::vector<std::string>, std::uint32_t>{{}, 932'067},
          std::pair<std::vector<std::string>, std::uint32_t>{{"--trace-memory", "1"}, 14'563}}) {
        DaemonOptions o;
        o.extra_args = args;
        auto d = Daemon::start(o);
        ASSERT_NE(d, nullptr);
        apci_board* b = nullptr;
        ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK) << apci_last_error(nullptr);
        ASSERT_EQ(apci_trace_enable(b, 16), APCI_OK) << apci_last_error(b);
        ASSERT_EQ(apci_step(b, 10, nullptr), APCI_OK) << apci_last_error(b);
        EXPECT_EQ(apci_trace_enable(b, fits + 1), APCI_NO_MEMORY) << fits;
        const std::string why = apci_last_error(b);
        EXPECT_TRUE(contains(why, "a trace ring of " + std::to_string(fits + 1) + " samples"))
            << why;
        EXPECT_TRUE(contains(why, "rwmos-emu --trace-memory")) << why;
        apci_motion_status st{};
        ASSERT_EQ(apci_motion_status_get(b, &st), APCI_OK);
        EXPECT_EQ(st.trace_pending, 10u) << "the refusal dropped the samples";
        EXPECT_NE(st.flags & APCI_MOTION_TRACING, 0u);
        EXPECT_EQ(apci_trace_enable(b, fits), APCI_OK) << fits << ": " << apci_last_error(b);
        EXPECT_EQ(apci_trace_enable(b, 0), APCI_OK);
        apci_close(b);
        EXPECT_EQ(d->stop(), 0);
    }
}

// Under a memory limit a request that runs out of memory (std::bad_alloc) ended the daemon,
// leaving its registry entry behind, and every client lost the board. Now that request is
// answered NoMemory with a reason, counted, and everything else goes on. The limit here: the
// daemon's address space held to what it has plus 48 MiB, a trace allowed 1152 MiB.
// (The sanitizers' allocators do not return what they cannot get: skipped under them.)
TEST(DaemonMemory, ARequestThatRunsOutOfMemoryIsAnsweredNoMemoryAndTheDaemonStays) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    GTEST_SKIP() << "the sanitizers' allocators abort instead of failing an allocation";
#endif
    DaemonOptions o;
    o.extra_args = {"--trace-memory", "1152"};
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    std::ifstream status("/proc/" + std::to_string(d->pid()) + "/status");
    std::uint64_t vm_kb = 0;
    for (std::string line; std::getline(status, line);)
        if (line.starts_with("VmSize:")) vm_kb = std::stoull(line.substr(7));
    ASSERT_GT(vm_kb, 0u);
    const rlimit cap{(vm_kb << 10) + (48u << 20), (vm_kb << 10) + (48u << 20)};
    ASSERT_EQ(::prlimit(d->pid(), RLIMIT_AS, &cap, nullptr), 0);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    ASSERT_EQ(apci_set_timeout(b, 60'000), APCI_OK);
    ASSERT_EQ(apci_trace_enable(b, 1u << 24), APCI_OK) << apci_last_error(b);
    // 2^20 samples (75 MB) do not fit in 48 MiB.
    EXPECT_EQ(apci_step(b, objif::kMaxClockCycles, nullptr), APCI_NO_MEMORY);
    EXPECT_TRUE(contains(apci_last_error(b), "out of memory")) << apci_last_error(b);
    EXPECT_EQ(apci_trace_enable(b, 0), APCI_OK) << apci_last_error(b);
    // The board serves this client and others as before.
    apci_object_descriptor axes{1000, 0, 3, 0, 0};
    std::int32_t n = 0;
    EXPECT_EQ(apci_read_int(b, &axes, &n), APCI_OK) << apci_last_error(b);
    apci_close(b);
    EXPECT_GT(status_of(d->unix_uri()).now, 0u);
    EXPECT_TRUE(std::filesystem::exists(d->dir().file("rwmos-emu." + std::to_string(d->pid()))));
    EXPECT_EQ(d->stop(), 0);
    EXPECT_TRUE(contains(d->log(), "(1 answered with Error)")) << d->log();
    EXPECT_FALSE(std::filesystem::exists(d->dir().file("rwmos-emu." + std::to_string(d->pid()))));
}

TEST(DaemonMemory, TraceMemoryOutOfRangeIsAUsageError) {
    apci_test::TempDir dir;
    for (const char* bad : {"0", "1153", "-1", "lots"}) {
        std::string out;
        EXPECT_EQ(apci_test::run_daemon({"--socket", dir.file("emu.sock"), "--trace-memory", bad},
                                        out, dir.path()),
                  2)
            << bad << ": " << out;
    }
}

// A client that asks for trace samples in hundreds of pipelined requests and reads none of
// the replies makes the daemon hold at most kMaxQueuedReplies (1 MiB) of them and what the
// socket takes: the rest stay in the ring until it reads. (All of the ring went into its
// unread replies at once: the ring's memory twice over, for one client.) Then it reads and
// gets every sample, in order.
TEST(DaemonMemory, AClientThatDoesNotReadItsTraceRepliesHoldsAtMostTheReplyBound) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    constexpr std::uint64_t kSamples = 400'000;  // 28.8 MB in the ring
    {
        apci_board* b = nullptr;
        ASSERT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_OK);
        ASSERT_EQ(apci_set_timeout(b, 60'000), APCI_OK);
        ASSERT_EQ(apci_trace_enable(b, kSamples), APCI_OK) << apci_last_error(b);
        ASSERT_EQ(apci_step(b, kSamples, nullptr), APCI_OK) << apci_last_error(b);
        apci_close(b);
    }
    RawClient reader(d->socket_path());
    constexpr std::uint32_t kRequests = 600;  // more than it takes to empty the ring
    std::vector<std::uint8_t> requests;
    for (std::uint32_t i = 0; i < kRequests; ++i) {
        const auto f = trace_frame(1 + i, static_cast<std::uint32_t>(objif::kMaxSamplesPerReply));
        requests.insert(requests.end(), f.begin(), f.end());
    }
    ASSERT_TRUE(reader.send(requests));
    std::this_thread::sleep_for(300ms);  // time for the daemon to serve what it would
    const apci_motion_status st = status_of(d->unix_uri());
    // At most 1 MiB queued plus what the socket's buffers hold went out of the ring.
    constexpr std::uint64_t kUnreadBound = (std::uint64_t{4} << 20) / objif::kWireSampleSize;
    EXPECT_GE(st.trace_pending, kSamples - kUnreadBound)
        << "the daemon drained the ring into replies nobody reads";

    std::uint64_t cycle = 0;
    std::uint64_t received = 0;
    for (std::uint32_t i = 0; i < kRequests; ++i) {
        objif::Frame frame;
        ASSERT_TRUE(reader.receive(frame, 60s)) << "reply " << i;
        ASSERT_EQ(frame.sequence, 1 + i);
        objif::TraceReply reply;
        ASSERT_EQ(objif::decode(frame.payload, reply), objif::FrameError::kNone);
        for (const auto& s : reply.samples) {
            ASSERT_EQ(s.cycle, ++cycle);
            ++received;
        }
    }
    EXPECT_EQ(received, kSamples);
    EXPECT_EQ(d->stop(), 0);
}

// ---- Descriptors

// The daemon's open-files limit lowered under it (as `ulimit -n 64` with 64 clients did):
// every newcomer beyond what the descriptors allow is told why and closed (it was left in the
// listen backlog: the daemon spun on the ready listener, 53 % CPU and 50 MB of log in 2 s, and
// the newcomer was told the daemon was not one); the others keep working, and once clients go
// newcomers are served again.
TEST(DaemonDescriptors, OutOfFileDescriptorsANewcomerIsToldWhyAndTheDaemonDoesNotSpin) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    const rlimit low{24, 24};
    ASSERT_EQ(::prlimit(d->pid(), RLIMIT_NOFILE, &low, nullptr), 0);
    std::vector<std::unique_ptr<RawClient>> greeted;
    std::size_t refused = 0;
    for (int i = 0; i < 40; ++i) {
        auto c = std::make_unique<RawClient>(d->socket_path());
        ASSERT_TRUE(c->connected());
        objif::Frame frame;
        ASSERT_TRUE(c->receive_any(frame, 10s)) << "client " << i << " was told nothing";
        objif::Notice notice;
        ASSERT_EQ(objif::decode(frame.payload, notice), objif::FrameError::kNone);
        if (notice.status == objif::Status::kOk) {
            greeted.push_back(std::move(c));
            continue;
        }
        EXPECT_EQ(notice.status, objif::Status::kTransportError);
        EXPECT_TRUE(notice.text.starts_with("out of file descriptors (")) << notice.text;
        EXPECT_TRUE(contains(notice.text, "limit 24 open files")) << notice.text;
        EXPECT_TRUE(c->closed_by_peer());
        ++refused;
    }
    EXPECT_GT(greeted.size(), 4u);
    EXPECT_GT(refused, 4u);
    // The C API's newcomer, at the limit, is told the daemon's reason. At the limit: raw
    // newcomers until one is refused (a descriptor the daemon held for a moment while the
    // others came, under ThreadSanitizer's runtime say, may have come free since).
    for (int i = 0; i < 8; ++i) {
        auto c = std::make_unique<RawClient>(d->socket_path());
        objif::Frame frame;
        objif::Notice notice;
        ASSERT_TRUE(c->receive_any(frame, 10s));
        ASSERT_EQ(objif::decode(frame.payload, notice), objif::FrameError::kNone);
        if (notice.status != objif::Status::kOk) break;
        greeted.push_back(std::move(c));
    }
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open(d->unix_uri().c_str(), &b), APCI_TRANSPORT_ERROR)
        << "the daemon's descriptors: " << descriptors_of(d->pid()) << "\n" << d->log();
    EXPECT_TRUE(
        contains(apci_last_error(nullptr), "refused the connection: out of file descriptors"))
        << apci_last_error(nullptr);

    // Nothing is left waiting: the daemon sleeps (its CPU time hardly moves) and logs a line
    // now and then, not one per turn of its loop.
    const auto cpu_ticks = [&] {
        std::ifstream stat("/proc/" + std::to_string(d->pid()) + "/stat");
        std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
        std::istringstream fields(text.substr(text.rfind(')') + 2));
        std::string field;
        std::uint64_t ticks = 0;
        for (int i = 3; i <= 15 && fields >> field; ++i)
            if (i == 14 || i == 15) ticks += std::stoull(field);  // utime, stime
        return ticks;
    };
    const std::uint64_t before = cpu_ticks();
    std::this_thread::sleep_for(1s);
    EXPECT_LT(cpu_ticks() - before, static_cast<std::uint64_t>(::sysconf(_SC_CLK_TCK)) / 4)
        << "the daemon spins";
    EXPECT_LE(count_of(d->log(), "out of file descriptors") + count_of(d->log(), "Too many open"),
              4u)
        << d->log();

    // The greeted ones are served; once two go, a newcomer is greeted again.
    objif::Frame frame;
    ASSERT_TRUE(greeted.front()->send(clock_frame(3, objif::ClockMode::kQuery, 0)));
    ASSERT_TRUE(greeted.front()->receive(frame));
    EXPECT_EQ(frame.sequence, 3u);
    greeted.pop_back();
    greeted.pop_back();
    EXPECT_TRUE(apci_test::eventually([&] {
        RawClient again(d->socket_path());
        objif::Notice notice;
        return again.receive_any(frame, 5s) &&
               objif::decode(frame.payload, notice) == objif::FrameError::kNone &&
               notice.status == objif::Status::kOk;
    }));
    greeted.clear();
    EXPECT_EQ(d->stop(), 0);
}

// The daemon's spare descriptor (/dev/null, opened close-on-exec), found in /proc; -1 when it
// has none.
int spare_of(pid_t pid) {
    std::error_code ec;
    const std::filesystem::path dir = "/proc/" + std::to_string(pid) + "/fd";
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        std::error_code link_ec;
        if (std::filesystem::read_symlink(entry.path(), link_ec) != "/dev/null") continue;
        std::ifstream info("/proc/" + std::to_string(pid) + "/fdinfo/" +
                           entry.path().filename().string());
        std::string key;
        std::string flags;
        while (info >> key >> flags)
            if (key == "flags:" && (std::stoul(flags, nullptr, 8) & O_CLOEXEC) != 0)
                return std::stoi(entry.path().filename().string());
    }
    return -1;
}

// The spare lost (the descriptor it gave up was taken before it was opened again: here the
// open-files limit is lowered to the spare's own number, so once the numbers below it are
// taken, neither a newcomer nor the spare fits): the descriptor that comes free next goes to
// the spare before any newcomer, so the newcomers beyond the limit are still told why (the
// freed descriptor went to the first of them, and the next was told nothing).
TEST(DaemonDescriptors, ASpareLostIsTakenAgainBeforeTheNextNewcomer) {
    auto d = Daemon::start();
    ASSERT_NE(d, nullptr);
    // Served once, and the connection that saw it start gone (two sockets left: its listener
    // and ours): the daemon's descriptors stay as they are while nobody comes.
    std::vector<std::unique_ptr<RawClient>> greeted;
    greeted.push_back(std::make_unique<RawClient>(d->socket_path()));
    RawClient& first = *greeted.back();  // (cppcheck 2.10 cannot parse back()->f(x, 10s))
    objif::Frame frame;
    ASSERT_TRUE(first.receive_any(frame, 10s));
    ASSERT_TRUE(daemon_test::is_greeting(frame));
    ASSERT_TRUE(apci_test::eventually(
        [&] { return count_of(descriptors_of(d->pid()), ":socket:") == 2; }))
        << descriptors_of(d->pid());
    rlimit original{};
    ASSERT_EQ(::prlimit(d->pid(), RLIMIT_NOFILE, nullptr, &original), 0);
    const auto limit_to = [&](rlim_t soft) {
        const rlimit l{soft, original.rlim_max};
        return ::prlimit(d->pid(), RLIMIT_NOFILE, &l, nullptr) == 0;
    };
    int spare = spare_of(d->pid());
    ASSERT_GE(spare, 3) << descriptors_of(d->pid());
    ASSERT_TRUE(limit_to(static_cast<rlim_t>(spare)));
    // Newcomers take the free numbers below the spare's (greeted) until one finds none: the
    // spare, given up for it, does not fit again, and the newcomer is told nothing.
    std::vector<std::unique_ptr<RawClient>> waiting;
    for (int i = 0; i < 64 && !contains(d->log(), "no spare descriptor"); ++i) {
        auto c = std::make_unique<RawClient>(d->socket_path());
        ASSERT_TRUE(c->connected());
        bool told = false;
        ASSERT_TRUE(apci_test::eventually([&] {
            told = c->receive_any(frame, 20ms);
            return told || contains(d->log(), "no spare descriptor");
        })) << "client " << i << ": " << descriptors_of(d->pid()) << "\n" << d->log();
        if (!told) {
            waiting.push_back(std::move(c));
        } else if (daemon_test::is_greeting(frame)) {
            greeted.push_back(std::move(c));
        } else {
            // Refused on a spare that moved to a number below (one the daemon held for a
            // moment, under ThreadSanitizer's runtime say, came free): the limit follows it.
            ASSERT_TRUE(apci_test::eventually([&] { return spare_of(d->pid()) >= 3; }));
            spare = spare_of(d->pid());
            ASSERT_TRUE(limit_to(static_cast<rlim_t>(spare)));
        }
    }
    ASSERT_FALSE(waiting.empty()) << descriptors_of(d->pid()) << "\n" << d->log();
    EXPECT_EQ(spare_of(d->pid()), -1) << descriptors_of(d->pid());
    // Room for one descriptor more: it goes to the spare, and each newcomer waiting is told
    // why; so is the next one.
    ASSERT_TRUE(limit_to(static_cast<rlim_t>(spare) + 1));
    const auto refused = [&](RawClient& c) {
        objif::Notice notice;
        return c.receive_any(frame, 10s) &&
               objif::decode(frame.payload, notice) == objif::FrameError::kNone &&
               notice.status == objif::Status::kTransportError &&
               notice.text.starts_with("out of file descriptors (") && c.closed_by_peer();
    };
    for (const auto& c : waiting)
        EXPECT_TRUE(refused(*c)) << descriptors_of(d->pid()) << "\n" << d->log();
    RawClient next(d->socket_path());
    EXPECT_TRUE(refused(next)) << descriptors_of(d->pid()) << "\n" << d->log();
    // (The daemon gives the spare up for a moment whenever it accepts at the limit.)
    EXPECT_TRUE(apci_test::eventually([&] { return spare_of(d->pid()) == spare; }))
        << descriptors_of(d->pid());
    // The limit as it was: newcomers are greeted again.
    ASSERT_TRUE(limit_to(original.rlim_cur));
    RawClient later(d->socket_path());
    ASSERT_TRUE(later.receive_any(frame, 10s));
    EXPECT_TRUE(daemon_test::is_greeting(frame));
    greeted.clear();
    EXPECT_EQ(d->stop(), 0);
}

// The default --max-clients of up to 4096 met a soft limit of 1024 open files: the daemon
// raises its soft limit to the hard one, and where that is too small it says what happens.
TEST(DaemonDescriptors, AnOpenFilesLimitBelowMaxClientsIsRaisedOrNamed) {
    apci_test::TempDir dir;
    const std::string log_path = dir.file("log");
    const auto start = [&](rlim_t soft, rlim_t hard) {
        const pid_t pid = ::fork();
        if (pid == 0) {
            const rlimit limit{soft, hard};
            const int out =
                ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
            if (::setrlimit(RLIMIT_NOFILE, &limit) != 0 || out < 0 || ::dup2(out, 2) < 0)
                ::_exit(126);
            ::setenv("APCI_RUNTIME_DIR", dir.path().c_str(), 1);
            ::execl(apci_test::daemon_binary(), apci_test::daemon_binary(), "--socket",
                    dir.file("emu.sock").c_str(), "--max-clients", "4096", nullptr);
            ::_exit(127);
        }
        return pid;
    };
    const auto read_log = [&] {
        std::ifstream in(log_path);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    const auto stop = [](pid_t pid) {
        ::kill(pid, SIGTERM);
        int status = 0;
        ::waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    // Hard limit 256: raised to it, and still too small: named.
    pid_t pid = start(64, 256);
    ASSERT_GT(pid, 0);
    EXPECT_TRUE(apci_test::eventually([&] { return contains(read_log(), "serving one board"); }));
    const std::string limits = "/proc/" + std::to_string(pid) + "/limits";
    std::ifstream proc_limits(limits);
    std::string line;
    std::string soft, hard;
    while (std::getline(proc_limits, line))
        if (line.starts_with("Max open files")) std::istringstream(line.substr(14)) >> soft >> hard;
    EXPECT_EQ(soft, "256") << "the soft limit was not raised to the hard one";
    EXPECT_EQ(hard, "256");
    EXPECT_EQ(stop(pid), 0);
    EXPECT_TRUE(contains(read_log(),
                         "--max-clients 4096 needs about 4112 open files, the limit "
                         "is 256 (ulimit -n): clients beyond about 240 are told the "
                         "daemon is out of file descriptors"))
        << read_log();
    // A hard limit that suffices: raised, no warning.
    std::filesystem::remove(log_path);
    pid = start(64, 8192);
    ASSERT_GT(pid, 0);
    EXPECT_TRUE(apci_test::eventually([&] { return contains(read_log(), "serving one board"); }));
    EXPECT_EQ(stop(pid), 0);
    EXPECT_FALSE(contains(read_log(), "needs about")) << read_log();
}

}  // namespace
