// SPDX-License-Identifier: MIT
// The motion claim on one daemon (docs/motion-claim.md, docs/rwmos-emu.md "Clients and
// robustness"): one client claims the board's motion; another's claim is refused naming the
// holder, and so is each of its requests that starts or changes motion, with nothing changed;
// reads stay open to everyone; the claim ends when the holder releases it, closes, or is
// killed (SIGKILL: nothing is released by the client, the daemon sees the connection end);
// mailbox hosts are known by their process. And `apcictl run` twice at once on one daemon:
// the second is refused naming the first and moves nothing; the first completes whole.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.h"
#include "apcictl.h"
#include "daemon.h"
#include "objif/frame.h"
#include "raw_client.h"
#include "rwmos/board.h"
#include "rwmos/frame_server.h"
#include "text.h"

namespace {

using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::TempDir;
using test_support::contains;
using namespace std::chrono_literals;

struct Client {
    apci_board* board = nullptr;
    explicit Client(const std::string& uri) {
        EXPECT_EQ(apci_open(uri.c_str(), &board), APCI_OK) << apci_last_error(nullptr);
    }
    ~Client() { apci_close(board); }
    Client(const Client&) = delete;
    Client& operator=(const Client&) = delete;
    std::string error() const { return apci_last_error(board); }
    apci_motion_claim claim() {
        apci_motion_claim c{};
        EXPECT_EQ(apci_motion_claim_get(board, &c), APCI_OK) << error();
        return c;
    }
    std::uint64_t now() {
        apci_motion_status st{};
        EXPECT_EQ(apci_motion_status_get(board, &st), APCI_OK) << error();
        return st.now;
    }
};

// TC group 1's RADIUS, which every client may read.
apci_object_descriptor radius() {
    return apci_object_descriptor{APCI_TC_BUS, APCI_TC_DEVICE_GROUP, 1, APCI_TC_RADIUS, 0};
}

std::string self_holder() {
    return fmt::format("the board's motion is held by pid {} (", ::getpid());
}

class MotionClaimDaemon : public ::testing::Test {
protected:
    void SetUp() override {
        DaemonOptions o;
        o.shm = true;
        daemon_ = Daemon::start(o);
        ASSERT_NE(daemon_, nullptr);
    }
    std::unique_ptr<Daemon> daemon_;
};

TEST_F(MotionClaimDaemon, SecondClientsClaimIsRefusedNamingTheHolder) {
    Client a(daemon_->unix_uri()), b(daemon_->unix_uri());
    EXPECT_EQ(a.claim().held, 0);
    ASSERT_EQ(apci_claim_motion(a.board), APCI_OK) << a.error();
    EXPECT_EQ(apci_claim_motion(b.board), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(b.error(), self_holder())) << b.error();
    EXPECT_TRUE(contains(b.error(), " since 20")) << b.error();
    const apci_motion_claim seen = b.claim();
    EXPECT_EQ(seen.held, 1);
    EXPECT_EQ(seen.yours, 0);
    EXPECT_EQ(seen.pid, ::getpid());
    const apci_motion_claim own = a.claim();
    EXPECT_EQ(own.yours, 1);
    EXPECT_EQ(own.since_ms, seen.since_ms);
    // The refused handle holds nothing: its release is one without a claim.
    EXPECT_EQ(apci_release_motion(b.board), APCI_WRONG_DEVICE_STATE);
    EXPECT_EQ(a.claim().yours, 1);
}

TEST_F(MotionClaimDaemon, NonHoldersMotionRequestsAreRefusedAndChangeNothing) {
    Client a(daemon_->unix_uri()), b(daemon_->unix_uri());
    apci_object_descriptor r = radius();
    ASSERT_EQ(apci_write_double(a.board, &r, 2.5), APCI_OK) << a.error();
    ASSERT_EQ(apci_claim_motion(a.board), APCI_OK) << a.error();
    const std::uint64_t before = a.now();

    apci_object_descriptor rb = radius();
    EXPECT_EQ(apci_write_double(b.board, &rb, 7.0), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(b.error(), self_holder())) << b.error();
    apci_profile p{};
    p.kind = APCI_PROFILE_LINE;
    p.axes = 0x01;
    p.feed = 600.0;
    p.target[0] = 10.0;
    EXPECT_EQ(apci_spool_profile(b.board, &p, nullptr), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(b.error(), self_holder())) << b.error();
    apci_direct_command ja{};
    ja.code = APCI_DIRECT_JA;
    ja.axes = 0x01;
    ja.target[0] = 3.0;
    EXPECT_EQ(apci_direct_command_send(b.board, &ja), APCI_MOTION_CLAIMED);
    EXPECT_EQ(apci_ssf_command(b.board, 0x03, APCI_SSF_RELEASE_HELD_PROFILE, nullptr),
              APCI_MOTION_CLAIMED);
    apci_motion_status st{};
    EXPECT_EQ(apci_step(b.board, 100, &st), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(b.error(), self_holder())) << b.error();
    EXPECT_EQ(apci_run_until_idle(b.board, 100, &st), APCI_MOTION_CLAIMED);
    EXPECT_EQ(apci_trace_enable(b.board, 16), APCI_MOTION_CLAIMED);
    apci_segment seg[2];
    size_t n = 99;
    EXPECT_EQ(apci_read_segments(b.board, seg, 2, &n), APCI_MOTION_CLAIMED);
    apci_trace_sample sample[2];
    EXPECT_EQ(apci_read_trace(b.board, sample, 2, &n), APCI_MOTION_CLAIMED);

    // Nothing of it reached the board.
    double value = 0;
    ASSERT_EQ(apci_read_double(a.board, &r, &value), APCI_OK);
    EXPECT_EQ(value, 2.5);
    ASSERT_EQ(apci_motion_status_get(a.board, &st), APCI_OK);
    EXPECT_EQ(st.now, before);
    EXPECT_EQ(st.fill, 0u);
    EXPECT_EQ(st.position[0], 0.0);
    EXPECT_EQ(st.flags & APCI_MOTION_TRACING, 0u);
}

TEST_F(MotionClaimDaemon, HolderMovesWhileOthersRead) {
    Client a(daemon_->unix_uri()), b(daemon_->unix_uri());
    ASSERT_EQ(apci_claim_motion(a.board), APCI_OK);
    apci_profile p{};
    p.kind = APCI_PROFILE_LINE;
    p.axes = 0x01;
    p.feed = 600.0;
    p.target[0] = 10.0;
    ASSERT_EQ(apci_spool_profile(a.board, &p, nullptr), APCI_OK) << a.error();
    apci_motion_status st{};
    ASSERT_EQ(apci_step(a.board, 500, &st), APCI_OK) << a.error();
    // Reads and the motion status stay open to the other client.
    apci_motion_status seen{};
    ASSERT_EQ(apci_motion_status_get(b.board, &seen), APCI_OK) << b.error();
    EXPECT_EQ(seen.now, st.now);
    EXPECT_EQ(seen.position[0], st.position[0]);
    apci_object_descriptor r = radius();
    double value = -1;
    EXPECT_EQ(apci_read_double(b.board, &r, &value), APCI_OK) << b.error();
    uint32_t fill = 0, capacity = 0;
    EXPECT_EQ(apci_spooler_fill(b.board, &fill, &capacity), APCI_OK) << b.error();
    EXPECT_EQ(fill, 1u);
    // And so does `apcictl status`.
    const auto status = test_support::apcictl({"--device", daemon_->unix_uri(), "status"});
    EXPECT_EQ(status.exit_code, 0) << status.err;
    EXPECT_TRUE(contains(status.out, "spooler 1 of")) << status.out;
    ASSERT_EQ(apci_run_until_idle(a.board, 1'000'000, &st), APCI_OK);
    EXPECT_EQ(st.position[0], 10.0);
    apci_segment seg[2];
    size_t n = 0;
    ASSERT_EQ(apci_read_segments(a.board, seg, 2, &n), APCI_OK);
    EXPECT_EQ(n, 1u);
}

TEST_F(MotionClaimDaemon, ReleaseAndCloseEachGiveTheClaimBack) {
    Client b(daemon_->unix_uri());
    {
        Client a(daemon_->unix_uri());
        ASSERT_EQ(apci_claim_motion(a.board), APCI_OK);
        ASSERT_EQ(apci_release_motion(a.board), APCI_OK) << a.error();
        ASSERT_EQ(apci_claim_motion(b.board), APCI_OK) << b.error();
        ASSERT_EQ(apci_release_motion(b.board), APCI_OK);
        ASSERT_EQ(apci_claim_motion(a.board), APCI_OK) << a.error();
        EXPECT_EQ(apci_claim_motion(b.board), APCI_MOTION_CLAIMED);
    }  // a closes holding it
    EXPECT_EQ(apci_claim_motion(b.board), APCI_OK) << b.error();
}

// A child process that opens `uri`, claims the motion, tells the parent on `ready` and waits
// to be killed.
// With `comm`, the child's command name is that first (prctl PR_SET_NAME).
pid_t claiming_child(const std::string& uri, const char* comm = nullptr) {
    int ready[2];
    if (::pipe(ready) != 0) return -1;
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(ready[0]);
        if (comm != nullptr) (void)::prctl(PR_SET_NAME, comm, 0, 0, 0);
        apci_board* board = nullptr;
        const char ok = apci_open(uri.c_str(), &board) == APCI_OK &&
                                apci_claim_motion(board) == APCI_OK
                            ? 'y'
                            : 'n';
        (void)!::write(ready[1], &ok, 1);
        for (;;) ::pause();
    }
    ::close(ready[1]);
    char got = 0;
    const bool ok = pid > 0 && ::read(ready[0], &got, 1) == 1 && got == 'y';
    ::close(ready[0]);
    if (!ok && pid > 0) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        return -1;
    }
    return pid;
}

void kill_and_reap(pid_t pid) {
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
}

TEST_F(MotionClaimDaemon, ClaimOfAKilledClientEndsWithItsConnection) {
    const pid_t child = claiming_child(daemon_->unix_uri());
    ASSERT_GT(child, 0);
    Client b(daemon_->unix_uri());
    EXPECT_EQ(apci_claim_motion(b.board), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(b.error(), fmt::format("held by pid {} (", child))) << b.error();
    kill_and_reap(child);
    // The daemon sees the connection end; nothing else is needed.
    EXPECT_TRUE(apci_test::eventually([&] { return apci_claim_motion(b.board) == APCI_OK; }))
        << b.error();
    EXPECT_EQ(b.claim().yours, 1);
    EXPECT_TRUE(contains(daemon_->log(), "closed while it held the board's motion: released"))
        << daemon_->log();
}

TEST_F(MotionClaimDaemon, MailboxHostsClaimIsItsProcesssAndEndsWithIt) {
    const pid_t child = claiming_child(daemon_->shm_uri());
    ASSERT_GT(child, 0);
    Client sock(daemon_->unix_uri());
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(sock.error(), fmt::format("held by pid {} (", child))) << sock.error();
    apci_object_descriptor r = radius();
    EXPECT_EQ(apci_write_double(sock.board, &r, 1.0), APCI_MOTION_CLAIMED);
    // Another mailbox host of another process is refused as well; this process's own mailbox
    // handle is another host than the child.
    Client mail(daemon_->shm_uri());
    EXPECT_EQ(apci_write_double(mail.board, &r, 1.0), APCI_MOTION_CLAIMED);
    kill_and_reap(child);
    // The process is gone: its claim with it, at the next request that asks.
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_OK) << sock.error();
    // And a socket holder refuses a mailbox host's motion.
    EXPECT_EQ(apci_write_double(mail.board, &r, 1.0), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(mail.error(), self_holder())) << mail.error();
    EXPECT_EQ(apci_claim_motion(mail.board), APCI_MOTION_CLAIMED);
}

TEST_F(MotionClaimDaemon, MailboxHolderWhoseNameHoldsParenthesesAndSpacesIsKnown) {
    // /proc/PID/stat puts the command name in parentheses; a name with ") " in it must not
    // shift the fields after it (the start time that tells the holder alive).
    const pid_t child = claiming_child(daemon_->shm_uri(), "x) 1 2 3 4 5");
    ASSERT_GT(child, 0);
    Client sock(daemon_->unix_uri());
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_MOTION_CLAIMED);
    EXPECT_TRUE(contains(sock.error(), fmt::format("held by pid {} (x) 1 2 3 4 5)", child)))
        << sock.error();
    apci_object_descriptor r = radius();
    EXPECT_EQ(apci_write_double(sock.board, &r, 1.0), APCI_MOTION_CLAIMED);
    kill_and_reap(child);
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_OK) << sock.error();
}

// The child `make` starts (its pid, -1 on failure) made with the pid `pid` if the kernel gives
// it: the pid it hands out next is set through /proc/sys/kernel/ns_last_pid (as root); other
// processes may take it first, so a few tries. Its pid, or -1.
template <class Make>
pid_t child_with_pid(pid_t pid, Make make) {
    for (int attempt = 0; attempt < 200; ++attempt) {
        {
            std::ofstream last("/proc/sys/kernel/ns_last_pid");
            last << pid - 1;
            last.flush();
            if (!last) return -1;
        }
        const pid_t child = make();
        if (child == pid) return child;
        if (child > 0) kill_and_reap(child);
    }
    return -1;
}

pid_t idle_child() {
    const pid_t child = ::fork();
    if (child == 0) {
        for (;;) ::pause();
    }
    return child;
}

// A child that claimed the board's motion through the mailbox, seen holding it by `sock`, then
// killed; its pid (-1 where it could not be started), once a clock tick has passed, so that a
// process started from now on has a later start time.
pid_t dead_mailbox_holder(const std::string& shm_uri, Client& sock) {
    const pid_t holder = claiming_child(shm_uri);
    if (holder <= 0) return -1;
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_MOTION_CLAIMED);
    kill_and_reap(holder);
    std::this_thread::sleep_for(50ms);  // a clock tick is 10 ms at most
    return holder;
}

TEST_F(MotionClaimDaemon, ProcessThatGotADeadMailboxHoldersPidIsNotTheHolder) {
    Client sock(daemon_->unix_uri());
    const pid_t holder = dead_mailbox_holder(daemon_->shm_uri(), sock);
    ASSERT_GT(holder, 0);
    // Another process with the holder's pid, started later.
    const pid_t reborn = child_with_pid(holder, idle_child);
    if (reborn < 0) GTEST_SKIP() << "the kernel did not hand out pid " << holder << " again";
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_OK) << sock.error();
    kill_and_reap(reborn);
}

TEST_F(MotionClaimDaemon, ProcessThatGotADeadMailboxHoldersPidHoldsItsOwnClaim) {
    Client sock(daemon_->unix_uri());
    const pid_t holder = dead_mailbox_holder(daemon_->shm_uri(), sock);
    ASSERT_GT(holder, 0);
    // The next mailbox exchange is the new process's: its claim is its own, with its own start
    // time, and holds as long as it runs.
    const pid_t reborn =
        child_with_pid(holder, [&] { return claiming_child(daemon_->shm_uri()); });
    if (reborn < 0) GTEST_SKIP() << "the kernel did not hand out pid " << holder << " again";
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_MOTION_CLAIMED) << sock.error();
    apci_object_descriptor r = radius();
    EXPECT_EQ(apci_write_double(sock.board, &r, 1.0), APCI_MOTION_CLAIMED);
    kill_and_reap(reborn);
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_OK) << sock.error();
}

TEST_F(MotionClaimDaemon, MailboxHandleReleasesItsClaimWhenClosed) {
    Client sock(daemon_->unix_uri());
    {
        Client mail(daemon_->shm_uri());
        ASSERT_EQ(apci_claim_motion(mail.board), APCI_OK) << mail.error();
        EXPECT_EQ(apci_claim_motion(sock.board), APCI_MOTION_CLAIMED);
        // A second mailbox handle of the same process is the same host to the board, which
        // knows mailbox hosts by process: refused, and said so.
        Client mail2(daemon_->shm_uri());
        EXPECT_EQ(apci_claim_motion(mail2.board), APCI_MOTION_CLAIMED);
        EXPECT_TRUE(contains(mail2.error(), "another handle of this process")) << mail2.error();
    }
    EXPECT_EQ(apci_claim_motion(sock.board), APCI_OK) << sock.error();
}

// A MotionClaim request of `action` sent by a bare socket client (what libapci never sends
// where its handle knows the answer) and the daemon's reply.
bool raw_claim(daemon_test::RawClient& raw, objif::ClaimAction action, objif::ClaimReply& rep) {
    std::vector<std::uint8_t> payload;
    objif::encode(objif::ClaimRequest{action}, payload);
    if (!raw.send(daemon_test::frame_bytes(objif::Opcode::kMotionClaim, 7, payload))) return false;
    objif::Frame reply;
    if (!raw.receive(reply)) return false;
    EXPECT_EQ(reply.opcode, static_cast<std::uint16_t>(objif::Opcode::kMotionClaim) |
                                objif::kReplyFlag);
    EXPECT_EQ(reply.sequence, 7u);
    return objif::decode(reply.payload, rep) == objif::FrameError::kNone;
}

TEST_F(MotionClaimDaemon, AnotherClientsReleaseIsRefusedAndTheClaimStays) {
    Client a(daemon_->unix_uri());
    ASSERT_EQ(apci_claim_motion(a.board), APCI_OK) << a.error();
    daemon_test::RawClient raw(daemon_->socket_path());
    ASSERT_TRUE(raw.connected());
    objif::ClaimReply rep;
    ASSERT_TRUE(raw_claim(raw, objif::ClaimAction::kRelease, rep));
    EXPECT_EQ(rep.status, objif::Status::kWrongDeviceState);
    EXPECT_TRUE(rep.held);
    EXPECT_FALSE(rep.yours);
    EXPECT_EQ(rep.pid, ::getpid());
    // The holder still holds it, and a third client is still refused.
    EXPECT_EQ(a.claim().yours, 1);
    Client b(daemon_->unix_uri());
    EXPECT_EQ(apci_claim_motion(b.board), APCI_MOTION_CLAIMED);
    apci_object_descriptor r = radius();
    EXPECT_EQ(apci_write_double(b.board, &r, 3.0), APCI_MOTION_CLAIMED);
    // The holder's own release is served.
    ASSERT_TRUE(raw_claim(raw, objif::ClaimAction::kQuery, rep));
    EXPECT_EQ(rep.status, objif::Status::kOk);
    EXPECT_TRUE(rep.held);
    EXPECT_EQ(apci_release_motion(a.board), APCI_OK) << a.error();
    ASSERT_TRUE(raw_claim(raw, objif::ClaimAction::kQuery, rep));
    EXPECT_FALSE(rep.held);
}

TEST_F(MotionClaimDaemon, RefusedTraceReadSaysWhatWasAskedFor) {
    Client a(daemon_->unix_uri());
    ASSERT_EQ(apci_claim_motion(a.board), APCI_OK) << a.error();
    daemon_test::RawClient raw(daemon_->socket_path());
    ASSERT_TRUE(raw.connected());
    for (const objif::TraceKind what : {objif::TraceKind::kSegments, objif::TraceKind::kSamples}) {
        std::vector<std::uint8_t> payload;
        objif::encode(objif::TraceRequest{what, 4}, payload);
        ASSERT_TRUE(raw.send(daemon_test::frame_bytes(objif::Opcode::kReadTrace, 9, payload)));
        objif::Frame reply;
        ASSERT_TRUE(raw.receive(reply));
        EXPECT_EQ(reply.opcode,
                  static_cast<std::uint16_t>(objif::Opcode::kReadTrace) | objif::kReplyFlag);
        objif::TraceReply rep;
        ASSERT_EQ(objif::decode(reply.payload, rep), objif::FrameError::kNone);
        EXPECT_EQ(rep.status, objif::Status::kMotionClaimed);
        EXPECT_EQ(rep.what, what);
        EXPECT_TRUE(rep.samples.empty());
        EXPECT_TRUE(rep.segments.empty());
    }
}

TEST_F(MotionClaimDaemon, DeadMailboxHolderBlocksNoMotionRequest) {
    const pid_t child = claiming_child(daemon_->shm_uri());
    ASSERT_GT(child, 0);
    Client sock(daemon_->unix_uri());
    apci_object_descriptor r = radius();
    EXPECT_EQ(apci_write_double(sock.board, &r, 1.0), APCI_MOTION_CLAIMED);
    kill_and_reap(child);
    // The first request after the holder's end is a motion request, not a claim or a query:
    // the board finds the holder gone there too.
    EXPECT_EQ(apci_write_double(sock.board, &r, 2.0), APCI_OK) << sock.error();
    double value = 0;
    ASSERT_EQ(apci_read_double(sock.board, &r, &value), APCI_OK);
    EXPECT_EQ(value, 2.0);
}

// ---- apcictl run, twice at once on one daemon

// A program long enough that a second run starts while the first still runs: `blocks` lines
// back and forth on X.
std::string long_program(const TempDir& dir, int blocks) {
    const std::string path = dir.path() + "/long.nc";
    std::ofstream out(path);
    out << "G90 G01 F6000\n";
    for (int i = 1; i <= blocks; ++i) out << fmt::format("N{} X{} Y{}\n", i, i % 2 == 0 ? 0 : 10, i % 7);
    out << "M30\n";
    return path;
}

std::string segments_line(const std::string& out) {
    std::smatch m;
    if (!std::regex_search(out, m, std::regex(R"((\d+) blocks, (\d+) sent to the board, (\d+) segments executed)")))
        return {};
    return m[0];
}

TEST_F(MotionClaimDaemon, SecondApcictlRunIsRefusedAndTheFirstCompletesWhole) {
    TempDir dir;
    const std::string program = long_program(dir, 4000);
    // The program alone on a board of its own: what the first run must report.
    const auto alone = test_support::apcictl({"--device", "emu:", "run", program});
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    const std::string expected = segments_line(alone.out);
    ASSERT_FALSE(expected.empty()) << alone.out;

    // The first run in the background; the second once the daemon names the first as holder.
    test_support::ProcessResult first;
    std::thread first_run([&] {
        first = test_support::apcictl({"--device", daemon_->unix_uri(), "run", program});
    });
    Client watcher(daemon_->unix_uri());
    const bool held = apci_test::eventually([&] { return watcher.claim().held == 1; }, 30s);
    const apci_motion_claim holder = watcher.claim();
    const std::uint64_t now_before = watcher.now();
    test_support::ProcessResult second;
    if (held) second = test_support::apcictl({"--device", daemon_->unix_uri(), "run", program});
    first_run.join();
    ASSERT_TRUE(held) << "the first run never held the board's motion: " << first.out << first.err;
    const std::string first_out = first.out + first.err;

    EXPECT_EQ(second.exit_code, 1) << second.out << second.err;
    EXPECT_TRUE(contains(second.err,
                         fmt::format("apcictl: run: {}: the board's motion is held by pid {} "
                                     "(apcictl) since ",
                                     daemon_->unix_uri(), holder.pid)))
        << second.err;
    EXPECT_TRUE(contains(second.err, fmt::format("nothing was moved: wait until it has "
                                                 "finished, or stop it (kill {}), then run again",
                                                 holder.pid)))
        << second.err;
    EXPECT_EQ(second.out, "");  // no summary of a run that did not run
    EXPECT_EQ(first.exit_code, 0) << first_out;
    EXPECT_EQ(segments_line(first_out), expected) << first_out;
    EXPECT_TRUE(contains(first_out, "errors: none")) << first_out;
    // The board ran the first run's cycles only (the second stepped nothing): at least as
    // many as were run when the second was refused, and the claim ended with the run.
    EXPECT_GE(watcher.now(), now_before);
    EXPECT_EQ(watcher.claim().held, 0);
}

// `status` says who holds the board's motion, as a refused claim names the holder.
TEST_F(MotionClaimDaemon, StatusNamesTheHolderOfTheBoardsMotion) {
    const std::string uri = daemon_->unix_uri();
    auto r = test_support::apcictl({"--device", uri, "status"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "\nmotion: free\n")) << r.out;
    r = test_support::apcictl({"--device", uri, "status", "--json"});
    EXPECT_TRUE(contains(r.out, R"("motion":{"held":false,"served":true})")) << r.out;
    Client holder(uri);
    ASSERT_EQ(apci_claim_motion(holder.board), APCI_OK) << holder.error();
    const apci_motion_claim claim = holder.claim();
    r = test_support::apcictl({"--device", uri, "status"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, fmt::format("\nmotion: held by pid {} (", ::getpid()))) << r.out;
    EXPECT_TRUE(contains(r.out, " since 20")) << r.out;
    r = test_support::apcictl({"--device", uri, "status", "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, fmt::format(R"("held":true,"holder":"pid {} ()", ::getpid())))
        << r.out;
    EXPECT_TRUE(contains(r.out, fmt::format(R"("pid":{},"served":true,"since_ms":{}}})",
                                            ::getpid(), claim.since_ms)))
        << r.out;
    // The holder's command name as it is, no more (the record keeps 16 bytes, NULs after it).
    const std::string name = std::string(program_invocation_short_name).substr(0, 15);
    EXPECT_TRUE(contains(r.out, fmt::format(R"("holder":"pid {} ({}) since 20)", ::getpid(), name)))
        << r.out;
    EXPECT_TRUE(contains(r.out, fmt::format(R"("name":"{}","pid":{},)", name, ::getpid())))
        << r.out;
    ASSERT_EQ(apci_release_motion(holder.board), APCI_OK) << holder.error();
    r = test_support::apcictl({"--device", uri, "status"});
    EXPECT_TRUE(contains(r.out, "\nmotion: free\n")) << r.out;
}

TEST_F(MotionClaimDaemon, ApcictlRunOnAHeldBoardMovesNothing) {
    TempDir dir;
    const std::string program = long_program(dir, 5);
    Client holder(daemon_->unix_uri());
    ASSERT_EQ(apci_claim_motion(holder.board), APCI_OK);
    const std::uint64_t before = holder.now();
    const auto r = test_support::apcictl({"--device", daemon_->unix_uri(), "run", program});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.err, self_holder())) << r.err;
    EXPECT_TRUE(contains(r.err, fmt::format("(kill {})", ::getpid()))) << r.err;
    apci_motion_status st{};
    ASSERT_EQ(apci_motion_status_get(holder.board, &st), APCI_OK);
    EXPECT_EQ(st.now, before);
    EXPECT_EQ(st.fill, 0u);
    EXPECT_EQ(st.segments_pending, 0u);
    for (const double x : st.position) EXPECT_EQ(x, 0.0);
    // Released, the same run runs.
    ASSERT_EQ(apci_release_motion(holder.board), APCI_OK);
    const auto again = test_support::apcictl({"--device", daemon_->unix_uri(), "run", program});
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_TRUE(contains(again.out, "7 blocks, 7 sent to the board, 5 segments executed")) << again.out;
}

TEST_F(MotionClaimDaemon, ApcictlDiffClaimsBothBoards) {
    TempDir dir;
    const std::string program = long_program(dir, 3);
    Client holder(daemon_->unix_uri());
    ASSERT_EQ(apci_claim_motion(holder.board), APCI_OK);
    const auto r = test_support::apcictl(
        {"--device", "emu:", "diff", "--against", daemon_->unix_uri(), program});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "apcictl: diff: " + daemon_->unix_uri() + ": " + self_holder()))
        << r.err;
}

// ---- A board that does not serve MotionClaim (firmware or a bridge of before the claim)

// A socket server that greets as the daemon and serves an emulated board's frames, but answers
// MotionClaim UnknownOpcode as such a board does: one connection at a time, until stopped.
class BoardWithoutClaims {
public:
    explicit BoardWithoutClaims(const std::string& path) : path_(path) {
        listen_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
        ok_ = listen_ >= 0 && ::bind(listen_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
              ::listen(listen_, 4) == 0;
        if (ok_) thread_ = std::thread([this] { serve(); });
    }
    ~BoardWithoutClaims() {
        stop_ = true;
        ::shutdown(listen_, SHUT_RDWR);
        if (thread_.joinable()) thread_.join();
        if (listen_ >= 0) ::close(listen_);
    }
    BoardWithoutClaims(const BoardWithoutClaims&) = delete;
    BoardWithoutClaims& operator=(const BoardWithoutClaims&) = delete;
    bool ok() const { return ok_; }
    std::string uri() const { return "unix:" + path_; }

private:
    void serve() {
        rwmos::EmulatedBoard board;
        rwmos::FrameServer server(board);
        while (!stop_) {
            const int fd = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC);
            if (fd < 0) return;
            std::vector<std::uint8_t> out, payload, in;
            objif::encode(objif::Notice{objif::Status::kOk, std::string(objif::kDaemonGreeting)},
                          payload);
            objif::encode_frame(static_cast<std::uint16_t>(objif::Opcode::kNotice) |
                                    objif::kReplyFlag,
                                0, payload, out);
            (void)!::send(fd, out.data(), out.size(), MSG_NOSIGNAL);
            std::uint8_t chunk[65536];
            for (;;) {
                const ssize_t got = ::recv(fd, chunk, sizeof chunk, 0);
                if (got <= 0) break;
                in.insert(in.end(), chunk, chunk + got);
                out.clear();
                for (;;) {
                    objif::Frame frame;
                    std::size_t used = 0;
                    bool need_more = false;
                    if (objif::decode_frame(in, frame, used, need_more) != objif::FrameError::kNone)
                        break;
                    in.erase(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(used));
                    if (frame.opcode == static_cast<std::uint16_t>(objif::Opcode::kMotionClaim))
                        rwmos::FrameServer::reject(frame.sequence,
                                                   objif::FrameError::kUnknownOpcode, out);
                    else
                        (void)server.handle(frame, out);
                }
                if (!out.empty()) (void)!::send(fd, out.data(), out.size(), MSG_NOSIGNAL);
            }
            ::close(fd);
        }
    }

    std::string path_;
    int listen_ = -1;
    bool ok_ = false;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

TEST(MotionClaimWithoutSupport, ClaimIsNotSupportedAndApcictlRunGoesOnWithAWarning) {
    TempDir dir;
    BoardWithoutClaims board(dir.path() + "/old.sock");
    ASSERT_TRUE(board.ok());
    {
        Client c(board.uri());
        EXPECT_EQ(apci_claim_motion(c.board), APCI_NOT_SUPPORTED);
        EXPECT_TRUE(contains(c.error(), "the board does not serve motion claims")) << c.error();
        apci_motion_claim seen{};
        EXPECT_EQ(apci_motion_claim_get(c.board, &seen), APCI_NOT_SUPPORTED);
    }
    const std::string program = long_program(dir, 3);
    const auto r = test_support::apcictl({"--device", board.uri(), "run", program});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "apcictl: warning: run: " + board.uri() +
                                    " does not serve motion claims"))
        << r.err;
    EXPECT_TRUE(contains(r.out, "5 blocks, 5 sent to the board, 3 segments executed")) << r.out;
    // `status` says that nothing keeps two programs apart there.
    const auto s = test_support::apcictl({"--device", board.uri(), "status"});
    EXPECT_TRUE(contains(s.out, "\nmotion: " + board.uri() + " does not serve motion claims\n"))
        << s.out << s.err;
    const auto j = test_support::apcictl({"--device", board.uri(), "status", "--json"});
    EXPECT_TRUE(contains(j.out, R"("motion":{"served":false})")) << j.out << j.err;
}

}  // namespace
