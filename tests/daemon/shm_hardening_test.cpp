// SPDX-License-Identifier: MIT
// The dual-port RAM file against its neighbours (docs/hardening.md, "Daemon
// security"): a file shrunk (truncate) under the daemon or a client is an
// error on both sides, never a SIGBUS; the daemon creates its file only where
// nothing is, takes over only a stale mailbox file of its own, refuses a file
// with more than one name, and at exit removes only the file it served.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "apci/apci.h"
#include "daemon.h"
#include "objif/mailbox.h"
#include "objif/mapping_guard.h"
#include "other_user.h"
#include "text.h"

namespace {

using test_support::contains;

namespace mb = objif::mailbox;
using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::TempDir;

std::string bytes_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

unsigned mode_of(const std::string& path) {
    struct stat st {};
    EXPECT_EQ(::lstat(path.c_str(), &st), 0) << path;
    return st.st_mode & 07777;
}

// The bytes of a formatted mailbox whose board state says `state`: what a
// daemon leaves behind when it is killed (kServing) or a file to hand a client.
std::string mailbox_file(mb::BoardState state) {
    std::vector<std::uint32_t> words(mb::kWindowSize / 4);
    mb::MappedWindow w(words.data(), mb::kWindowSize, false);
    mb::format(w);
    mb::set_board_state(w, state);
    return {reinterpret_cast<const char*>(words.data()), mb::kWindowSize};
}

apci_object_descriptor axis_count() {
    return {1000, 0, 3, 0, 0};
}

bool alive(const Daemon& d) {
    int status = 0;
    return ::waitpid(d.pid(), &status, WNOHANG) == 0;
}

// ---- The guard (objif/mapping_guard.h)

TEST(ShmHardening, GuardTurnsABusErrorOnAShrunkFileIntoALostRegionOfZeros) {
    TempDir dir;
    const std::string path = dir.file("mapped");
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    write_bytes(path, std::string(3 * page, 'x'));
    const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    void* map =
        fd < 0 ? MAP_FAILED : ::mmap(nullptr, 3 * page, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (fd >= 0) ::close(fd);  // the mapping keeps the file
    if (map == MAP_FAILED) {
        ADD_FAILURE() << "cannot map " << path;
        return;
    }
    auto* bytes = static_cast<volatile std::uint8_t*>(map);
    {
        objif::MappingGuard guard(map, 3 * page);
        EXPECT_TRUE(guard.guarded());
        EXPECT_EQ(bytes[2 * page], 'x');
        EXPECT_FALSE(guard.lost());
        // A neighbour's truncate; without the guard the next access kills the test.
        if (guard.guarded() && ::truncate(path.c_str(), static_cast<off_t>(page)) == 0) {
            EXPECT_EQ(bytes[2 * page], 0) << "the page past the new end reads as zeros";
            bytes[2 * page + 1] = 7;  // and takes writes, which no longer reach the file
            EXPECT_EQ(bytes[2 * page + 1], 7);
            EXPECT_TRUE(guard.lost());
        } else {
            ADD_FAILURE() << "not guarded, or truncate failed";
        }
    }
    ::munmap(map, 3 * page);
    EXPECT_EQ(std::filesystem::file_size(path), page) << "the file is as the truncate left it";
}

TEST(ShmHardening, BusErrorOutsideEveryGuardedRegionStillKills) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    TempDir dir;
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    EXPECT_DEATH(
        {
            const std::string guarded_path = dir.file("guarded");
            const std::string bare_path = dir.file("bare");
            write_bytes(guarded_path, std::string(2 * page, 'g'));
            write_bytes(bare_path, std::string(2 * page, 'b'));
            const int g = ::open(guarded_path.c_str(), O_RDWR);
            const int b = ::open(bare_path.c_str(), O_RDWR);
            void* gm = ::mmap(nullptr, 2 * page, PROT_READ | PROT_WRITE, MAP_SHARED, g, 0);
            void* bm = ::mmap(nullptr, 2 * page, PROT_READ | PROT_WRITE, MAP_SHARED, b, 0);
            const objif::MappingGuard guard(gm, 2 * page);  // installs the handler
            if (::ftruncate(b, 0) != 0) std::abort();
            const volatile std::uint8_t* bare = static_cast<std::uint8_t*>(bm);
            std::fprintf(stderr, "%d\n", bare[page]);  // not guarded: SIGBUS kills as before
            std::exit(0);
        },
        "");
}

// ---- Point 1: a file shrunk under the daemon and its clients

TEST(ShmHardening, ClientWhoseFileIsTruncatedGetsATransportErrorNamingItNotACrash) {
    for (const off_t size : {off_t{4096}, off_t{0}}) {
        SCOPED_TRACE(size);
        TempDir dir;
        const std::string path = dir.file("dpram");
        // A mailbox marked serving whose board does not answer: the client alone meets the
        // truncate.
        write_bytes(path, mailbox_file(mb::BoardState::kServing));
        apci_board* b = nullptr;
        ASSERT_EQ(apci_open(("shm:" + path + "?timeout=200").c_str(), &b), APCI_OK)
            << apci_last_error(nullptr);
        ASSERT_EQ(::truncate(path.c_str(), size), 0);
        auto o = axis_count();
        std::int32_t v = 0;
        EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TRANSPORT_ERROR);
        EXPECT_TRUE(contains(apci_last_error(b), "was shrunk (truncated) by another process"))
            << apci_last_error(b);
        EXPECT_TRUE(contains(apci_last_error(b), path)) << apci_last_error(b);
        EXPECT_EQ(apci_is_connected(b), 0);
        EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TRANSPORT_ERROR) << "stays lost";
        apci_close(b);
        // A fresh open is refused with the size it found, before it maps anything.
        apci_board* again = nullptr;
        EXPECT_NE(apci_open(("shm:" + path).c_str(), &again), APCI_OK);
        EXPECT_TRUE(contains(apci_last_error(nullptr), "a mailbox window needs"))
            << apci_last_error(nullptr);
    }
}

TEST(ShmHardening, TruncatingTheFileUnderTheDaemonEndsOnlyItsServingOfTheFile) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    apci_board* shm = nullptr;
    apci_board* sock = nullptr;
    ASSERT_EQ(apci_open((d->shm_uri() + "?timeout=500").c_str(), &shm), APCI_OK)
        << apci_last_error(nullptr);
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &sock), APCI_OK) << apci_last_error(nullptr);
    auto obj = axis_count();
    std::int32_t v = 0;
    ASSERT_EQ(apci_read_int(shm, &obj, &v), APCI_OK) << apci_last_error(shm);

    ASSERT_EQ(::truncate(d->shm_path().c_str(), 4096), 0);
    EXPECT_TRUE(apci_test::eventually([&] { return contains(d->log(), "was shrunk"); }))
        << d->log();
    EXPECT_TRUE(contains(d->log(), "no longer serves the dual-port RAM file")) << d->log();
    EXPECT_TRUE(alive(*d)) << "the daemon survives: " << d->log();

    // The shm client gets an error and a lost link, and survives too.
    EXPECT_EQ(apci_read_int(shm, &obj, &v), APCI_TRANSPORT_ERROR);
    EXPECT_EQ(apci_is_connected(shm), 0) << apci_last_error(shm);
    apci_close(shm);

    // Socket clients, old and new, go on being served.
    v = 0;
    EXPECT_EQ(apci_read_int(sock, &obj, &v), APCI_OK) << apci_last_error(sock);
    EXPECT_EQ(v, 8);
    apci_board* fresh = nullptr;
    ASSERT_EQ(apci_open(d->unix_uri().c_str(), &fresh), APCI_OK) << apci_last_error(nullptr);
    EXPECT_EQ(apci_read_int(fresh, &obj, &v), APCI_OK) << apci_last_error(fresh);
    apci_close(fresh);
    apci_close(sock);
    EXPECT_TRUE(alive(*d));
    EXPECT_EQ(d->stop(), 0) << d->log();
    EXPECT_FALSE(std::filesystem::exists(d->shm_path())) << "its own file is still removed";
}

TEST(ShmHardening, FileTruncatedWhileAClientExchangesLeavesBothSidesStanding) {
    DaemonOptions o;
    o.socket = false;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open((d->shm_uri() + "?timeout=500").c_str(), &b), APCI_OK)
        << apci_last_error(nullptr);
    auto obj = axis_count();
    std::int32_t v = 0;
    apci_status last = APCI_OK;
    bool truncated = false;
    // Exchanges run while the file shrinks under both sides.
    for (int i = 0; i < 2000 && last == APCI_OK; ++i) {
        if (i == 100) {
            ASSERT_EQ(::truncate(d->shm_path().c_str(), 0), 0);
            truncated = true;
        }
        last = apci_read_int(b, &obj, &v);
    }
    EXPECT_TRUE(truncated);
    EXPECT_EQ(last, APCI_TRANSPORT_ERROR) << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 0);
    apci_close(b);
    EXPECT_TRUE(apci_test::eventually([&] { return contains(d->log(), "was shrunk"); }))
        << d->log();
    EXPECT_TRUE(alive(*d)) << d->log();
    EXPECT_EQ(d->stop(), 0) << d->log();
}

// ---- Point 2: whose file the path names

TEST(ShmHardening, ExistingUnrelatedFileIsRefusedAndLeftByteForByteWithItsMode) {
    TempDir dir;
    const std::string path = dir.file("notes.txt");
    const std::string precious = std::string("precious data\n") + std::string(5000, '\x7f');
    write_bytes(path, precious);
    ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--shm", path}, out, dir.path()), 1);
    EXPECT_TRUE(contains(out, "is not a dual-port RAM file of rwmos-emu")) << out;
    EXPECT_TRUE(contains(out, "left as it is")) << out;
    EXPECT_EQ(bytes_of(path), precious) << "not overwritten, not resized";
    EXPECT_EQ(mode_of(path), 0640u) << "mode unchanged";
}

TEST(ShmHardening, EmptyFileIsNotTakenOver) {
    TempDir dir;
    const std::string path = dir.file("empty");
    write_bytes(path, "");
    ASSERT_EQ(::chmod(path.c_str(), 0600), 0);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--shm", path}, out, dir.path()), 1);
    EXPECT_TRUE(contains(out, "is not a dual-port RAM file of rwmos-emu")) << out;
    EXPECT_EQ(std::filesystem::file_size(path), 0u);
    EXPECT_EQ(mode_of(path), 0600u);
}

TEST(ShmHardening, MailboxFileOfAnUnknownLayoutVersionIsRefused) {
    TempDir dir;
    const std::string path = dir.file("dpram");
    std::string file = mailbox_file(mb::BoardState::kStopped);
    file[mb::kOffVersion] = 99;
    write_bytes(path, file);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--shm", path}, out, dir.path()), 1);
    EXPECT_TRUE(contains(out, "layout version 99")) << out;
    EXPECT_EQ(bytes_of(path), file);
}

TEST(ShmHardening, HardLinkIsRefusedEvenToAMailboxFile) {
    TempDir dir;
    for (const bool ours : {false, true}) {
        SCOPED_TRACE(ours ? "a stale mailbox file" : "an unrelated file");
        const std::string target = dir.file(ours ? "stale-dpram" : "precious.bin");
        const std::string path = dir.file(ours ? "dpram-link" : "dpram");
        const std::string bytes = ours ? mailbox_file(mb::BoardState::kServing) : "keep me\n";
        write_bytes(target, bytes);
        ASSERT_EQ(::chmod(target.c_str(), 0644), 0);
        ASSERT_EQ(::link(target.c_str(), path.c_str()), 0);
        std::string out;
        EXPECT_EQ(apci_test::run_daemon({"--shm", path}, out, dir.path()), 1);
        EXPECT_TRUE(contains(out, "has 2 names (hard links)")) << out;
        EXPECT_EQ(bytes_of(target), bytes);
        EXPECT_EQ(mode_of(target), 0644u);
        EXPECT_TRUE(std::filesystem::exists(path)) << "the link is kept";
    }
}

TEST(ShmHardening, FifoAtThePathIsRefusedWithoutBlocking) {
    TempDir dir;
    const std::string path = dir.file("dpram");
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--shm", path}, out, dir.path()), 1);
    EXPECT_TRUE(contains(out, "is not a regular file")) << out;
    EXPECT_EQ(mode_of(path), static_cast<unsigned>(0600));
}

TEST(ShmHardening, StaleFileOfADaemonThatWasKilledIsTakenOverAndServed) {
    TempDir dir;
    const std::string path = dir.file("dpram");
    {
        DaemonOptions o;
        o.socket = false;
        o.shm = true;
        o.shm_path = path;
        auto killed = Daemon::start(o);
        ASSERT_NE(killed, nullptr);
        EXPECT_EQ(killed->stop(SIGKILL), 128 + SIGKILL);
    }
    ASSERT_TRUE(std::filesystem::exists(path)) << "a killed daemon leaves its file";
    ASSERT_EQ(::chmod(path.c_str(), 0600), 0);
    DaemonOptions o;
    o.socket = false;
    o.shm = true;
    o.shm_path = path;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    // The stale file already says "serving": wait for the daemon's own word.
    ASSERT_TRUE(apci_test::eventually([&] { return contains(d->log(), "serving one board"); }))
        << d->log();
    EXPECT_TRUE(contains(d->log(), "taking over the dual-port RAM file of a daemon that is gone"))
        << d->log();
    EXPECT_EQ(mode_of(path), 0660u);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(("shm:" + path).c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    auto obj = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(v, 8);
    apci_close(b);
    EXPECT_EQ(d->stop(), 0);
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ShmHardening, FilePutInPlaceOfTheServedOneIsNotRemovedAtExit) {
    DaemonOptions o;
    o.socket = false;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    const std::string other = d->dir().file("other");
    write_bytes(other, "someone else's file\n");
    ASSERT_EQ(::rename(other.c_str(), d->shm_path().c_str()), 0);
    EXPECT_EQ(d->stop(), 0) << d->log();
    EXPECT_EQ(bytes_of(d->shm_path()), "someone else's file\n") << "kept, untouched";
    EXPECT_TRUE(contains(d->log(), "is no longer the file this daemon served: left in place"))
        << d->log();
}

// ---- Whose file, as another user (the suite runs as root, where every file is its own)

// A stale mailbox file of another user's (left by nobody's daemon in a shared directory) is
// not taken over by root's daemon: refused, byte for byte and mode as it was. Root's stale
// file is not taken over by nobody's daemon either; nobody's own is.
TEST(ShmHardening, AStaleMailboxFileOfAnotherUserIsNotTakenOver) {
    if (!test_support::can_act_as_other_user()) GTEST_SKIP() << "needs root to act as another user";
    TempDir shared;
    ASSERT_EQ(::chmod(shared.path().c_str(), 01777), 0);
    const std::string theirs = shared.file("nobody.dpram");
    const std::string stale = mailbox_file(mb::BoardState::kServing);
    ASSERT_TRUE(test_support::as_other_user([&] {
        const int fd = ::open(theirs.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 || ::fchmod(fd, 0666) != 0) return false;
        const bool ok =
            ::write(fd, stale.data(), stale.size()) == static_cast<ssize_t>(stale.size());
        return ::close(fd) == 0 && ok;
    }));
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--shm", theirs}, out, shared.path()), 1) << out;
    EXPECT_TRUE(contains(out, theirs + " belongs to uid 65534, not to this daemon's user (uid 0)"))
        << out;
    EXPECT_TRUE(bytes_of(theirs) == stale) << "the file was changed";
    EXPECT_EQ(mode_of(theirs), 0666u);

    // The other way round: nobody's daemon and root's stale file, then nobody's own.
    const std::string roots = shared.file("root.dpram");
    write_bytes(roots, stale);
    ASSERT_EQ(::chmod(roots.c_str(), 0666), 0);
    const auto as_nobody = [&](const std::string& path, std::string& log) {
        const std::string log_path = shared.file("nobody.log");
        ::unlink(log_path.c_str());
        const bool served = test_support::as_other_user([&] {
            const std::string runtime = shared.file("nobody-run");
            ::mkdir(runtime.c_str(), 0700);
            ::setenv("APCI_RUNTIME_DIR", runtime.c_str(), 1);
            const pid_t daemon = ::fork();
            if (daemon == 0) {
                const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
                ::dup2(fd, 2);
                ::execl(apci_test::daemon_binary(), apci_test::daemon_binary(), "--shm",
                        path.c_str(), nullptr);
                ::_exit(127);
            }
            // Refused (it exits), or serving (its log says so; the stale file said so
            // before): then the board answers through the file, and the daemon is stopped.
            const auto serving = [&] {
                std::ifstream in(log_path);
                const std::string text((std::istreambuf_iterator<char>(in)),
                                       std::istreambuf_iterator<char>());
                return text.find("serving one board") != std::string::npos;
            };
            for (int i = 0; i < 1000 && !serving(); ++i) {
                if (::waitpid(daemon, nullptr, WNOHANG) == daemon) return false;  // refused
                ::usleep(10'000);
            }
            bool ok = false;
            apci_board* b = nullptr;
            if (serving() && apci_open(("shm:" + path).c_str(), &b) == APCI_OK) {
                auto obj = axis_count();
                std::int32_t v = 0;
                ok = apci_read_int(b, &obj, &v) == APCI_OK && v == 8;
                apci_close(b);
            }
            ::kill(daemon, SIGTERM);
            ::waitpid(daemon, nullptr, 0);
            return ok;
        });
        std::ifstream in(log_path);
        log.assign((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        return served;
    };
    std::string log;
    EXPECT_FALSE(as_nobody(roots, log)) << log;
    EXPECT_TRUE(contains(log, roots + " belongs to uid 0, not to this daemon's user (uid 65534)"))
        << log;
    EXPECT_TRUE(bytes_of(roots) == stale) << "the file was changed";
    EXPECT_TRUE(as_nobody(theirs, log)) << log;
    EXPECT_TRUE(contains(log, "taking over the dual-port RAM file of a daemon that is gone"))
        << log;
}

// ---- The host lock's token (the pid of the host holding it)

namespace {
// The host lock word of a served file, for the test to set.
class HostLock {
  public:
    explicit HostLock(const std::string& path) {
        fd_ = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
        if (fd_ >= 0)
            map_ = ::mmap(nullptr, mb::kWindowSize, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
    }
    ~HostLock() {
        if (map_ != MAP_FAILED) ::munmap(map_, mb::kWindowSize);
        if (fd_ >= 0) ::close(fd_);
    }
    HostLock(const HostLock&) = delete;
    HostLock& operator=(const HostLock&) = delete;
    bool ok() const noexcept { return map_ != MAP_FAILED; }
    void set(std::uint32_t token) {
        mb::MappedWindow(map_, mb::kWindowSize, true).store(mb::kOffHostLock, token);
    }
    std::uint32_t get() {
        return mb::MappedWindow(map_, mb::kWindowSize, true).load(mb::kOffHostLock);
    }

  private:
    int fd_ = -1;
    void* map_ = MAP_FAILED;
};

// A process that is not a host of any mailbox: /bin/sleep, started with nothing mapped.
pid_t start_sleeper() {
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::execl("/bin/sleep", "sleep", "30", nullptr);
        ::_exit(127);
    }
    return pid;
}
}  // namespace

// A lock left with a token no process can have (0xFFFFFFFF: kill(-1, 0) asks every process and
// always answers), or with the pid of a process that got it after the holder died (alive, but
// mapping no mailbox), is taken over: every host timed out on it for ever. A lock of a live
// host that maps the mailbox is waited for, as before.
TEST(ShmHardening, AHostLockOfNoProcessOrOfAReusedPidIsTakenOver) {
    DaemonOptions o;
    o.socket = false;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    HostLock lock(d->shm_path());
    ASSERT_TRUE(lock.ok());
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open((d->shm_uri() + "?timeout=2000").c_str(), &b), APCI_OK)
        << apci_last_error(nullptr);
    auto obj = axis_count();
    std::int32_t v = 0;
    for (const std::uint32_t token : {0xFFFFFFFFu, 0x80000000u, (1u << 22) + 1}) {
        lock.set(token);
        EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_OK) << token << ": " << apci_last_error(b);
        EXPECT_EQ(lock.get(), 0u);
    }
    const pid_t sleeper = start_sleeper();
    ASSERT_GT(sleeper, 0);
    lock.set(static_cast<std::uint32_t>(sleeper));
    EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(lock.get(), 0u);
    ::kill(sleeper, SIGKILL);
    ::waitpid(sleeper, nullptr, 0);

    // A live host: this process's child, which maps the file (inherited) and holds the lock.
    int ready[2];
    ASSERT_EQ(::pipe2(ready, O_CLOEXEC), 0);
    const pid_t host = ::fork();
    if (host == 0) {
        ::close(ready[0]);
        const char c = 'y';
        (void)!::write(ready[1], &c, 1);
        ::pause();
        ::_exit(0);
    }
    ::close(ready[1]);
    char c = 0;
    ASSERT_EQ(::read(ready[0], &c, 1), 1);
    ::close(ready[0]);
    lock.set(static_cast<std::uint32_t>(host));
    ASSERT_EQ(apci_set_timeout(b, 300), APCI_OK);
    EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_TIMEOUT);
    EXPECT_TRUE(contains(apci_last_error(b), "held by another host (token " + std::to_string(host)))
        << apci_last_error(b);
    EXPECT_EQ(lock.get(), static_cast<std::uint32_t>(host));
    ::kill(host, SIGKILL);
    ::waitpid(host, nullptr, 0);
    ASSERT_EQ(apci_set_timeout(b, 2000), APCI_OK);
    EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_OK) << apci_last_error(b);  // gone: taken over
    apci_close(b);
    EXPECT_EQ(d->stop(), 0);
}

}  // namespace
