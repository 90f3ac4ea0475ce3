// SPDX-License-Identifier: MIT
#include "shm_server.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "log.h"
#include "objif/byte_order.h"
#include "objif/frame.h"
#include "peer.h"

namespace rwmos_emu {

namespace mb = objif::mailbox;

namespace {
// After a request the board spins up to this long for the next one before it
// sleeps, so back-to-back requests are answered without a futex round trip;
// the budget shrinks while requests do not come that fast (AdaptiveSpin).
constexpr std::chrono::microseconds kShortestSpin{1};
constexpr std::chrono::microseconds kLongestSpin{50};
// Sleeps between looks at the mailbox. A host that can write but not wake
// the board (a PCI I/O BAR, read and written through sysfs) is noticed by
// these looks: within 1 ms while requests come, within 64 ms after a quiet
// spell; the sleep doubles while idle so an idle daemon wakes ~16 times a
// second. Hosts on a mapping wake the board at once (futex).
constexpr std::chrono::milliseconds kFirstSleep{1};
constexpr std::chrono::milliseconds kLongestSleep{64};

// Why an existing file at the path is not one this daemon may take over, as
// far as its inode tells ("" if it may be).
std::string refusal_by_inode(const std::string& path, const struct stat& st) {
    if (!S_ISREG(st.st_mode))
        return fmt::format(
            "{} is not a regular file: left as it is; remove it or choose another "
            "--shm path",
            path);
    if (st.st_nlink != 1)
        return fmt::format(
            "{} has {} names (hard links), so it is not taken over: left as it is; "
            "remove it or choose another --shm path",
            path, st.st_nlink);
    if (st.st_uid != ::geteuid())
        return fmt::format(
            "{} belongs to uid {}, not to this daemon's user (uid {}): left as it "
            "is; remove it or choose another --shm path",
            path, st.st_uid, ::geteuid());
    return {};
}

// Why an existing file is not a stale dual-port RAM file of a daemon ("" if
// it is one): it must start with the mailbox header (signature and a layout
// version this daemon knows).
std::string refusal_by_header(const std::string& path, int fd) {
    std::uint32_t header[2] = {};
    const ssize_t n = ::pread(fd, header, sizeof header, 0);
    if (n != static_cast<ssize_t>(sizeof header) || header[mb::kOffSignature / 4] != mb::kSignature)
        return fmt::format(
            "{} exists and is not a dual-port RAM file of rwmos-emu (no \"DRPM\" "
            "mailbox header): left as it is; remove it or choose another --shm path",
            path);
    if (const std::uint32_t version = header[mb::kOffVersion / 4];
        version == 0 || version > mb::kLayoutVersion)
        return fmt::format(
            "{} holds a mailbox of layout version {}, which this daemon does not "
            "know (it writes {}): left as it is; remove it or choose another --shm "
            "path",
            path, version, mb::kLayoutVersion);
    return {};
}

// Removes `path` if it still names the inode `st` describes.
void remove_if_same(const std::string& path, const struct stat& ours) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0 && st.st_dev == ours.st_dev && st.st_ino == ours.st_ino)
        ::unlink(path.c_str());
}

}  // namespace

ShmServer::~ShmServer() {
    stop();
}

bool ShmServer::open(const std::string& path, std::string& why) {
    // Created here, or else opened as it is: never through a symlink, never
    // truncated before it is known to be ours.
    // (Twice: a file removed between the two opens is created on the second round.)
    bool created = true;
    int fd = -1;
    for (int round = 0; round < 2 && fd < 0; ++round) {
        created = true;
        fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0660);
        if (fd < 0 && errno == EEXIST) {
            created = false;
            fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NOCTTY | O_NONBLOCK);
            if (fd < 0 && errno == ENOENT) continue;
        }
        break;
    }
    if (fd < 0) {
        const int err = errno;
        why = err == ELOOP ? fmt::format(
                                 "{} is a symbolic link: not followed, left as it is; "
                                 "give another --shm path",
                                 path)
                           : fmt::format("{}: {}", path, std::strerror(err));
        return false;
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        why = fmt::format("stat {}: {}", path, std::strerror(errno));
        ::close(fd);
        return false;
    }
    if (!created) {
        if (std::string refusal = refusal_by_inode(path, st); !refusal.empty()) {
            why = std::move(refusal);
            ::close(fd);
            return false;
        }
    }
    // Fails with undo: closes the file and removes it if this daemon created it.
    auto fail = [&](std::string text) {
        why = std::move(text);
        if (created) remove_if_same(path, st);
        ::close(fd);
        return false;
    };
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        return fail(err == EWOULDBLOCK
                        ? fmt::format("{} is served by another daemon; stop it first or choose "
                                      "another --shm",
                                      path)
                        : fmt::format("lock {}: {}", path, std::strerror(err)));
    }
    if (!created) {
        // Locked and not served: a daemon that served it is gone (crashed or killed).
        if (std::string refusal = refusal_by_header(path, fd); !refusal.empty())
            return fail(std::move(refusal));
        log(Level::kInfo, "{}: taking over the dual-port RAM file of a daemon that is gone", path);
    }
    if (::fchmod(fd, 0660) != 0 || ::ftruncate(fd, static_cast<off_t>(mb::kWindowSize)) != 0)
        return fail(fmt::format("{}: {}", path, std::strerror(errno)));
    void* map = ::mmap(nullptr, mb::kWindowSize, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (map == MAP_FAILED) return fail(fmt::format("mmap {}: {}", path, std::strerror(errno)));
    fd_ = fd;
    map_ = map;
    path_ = path;
    dev_ = st.st_dev;
    ino_ = st.st_ino;
    guard_ = std::make_unique<objif::MappingGuard>(map, mb::kWindowSize);
    if (!guard_->guarded())
        log(Level::kWarn, "{}: the mapping is not guarded: a truncate of the file kills the daemon",
            path);
    window_ = std::make_unique<mb::MappedWindow>(map, mb::kWindowSize, true);
    mb::format(*window_);
    return true;
}

void ShmServer::start() {
    if (!window_ || thread_.joinable()) return;
    stop_ = false;
    mb::set_board_state(*window_, mb::BoardState::kServing);
    thread_ = std::thread([this] { serve_loop(); });
}

std::string ShmServer::damage() const {
    struct stat st {};
    if (::fstat(fd_, &st) == 0 && st.st_size < static_cast<off_t>(mb::kWindowSize))
        return fmt::format("{} was shrunk to {} bytes by another process (the mailbox needs {})",
                           path_, st.st_size, mb::kWindowSize);
    if (guard_->lost())
        return fmt::format("{} was shrunk by another process while it was mapped", path_);
    if (window_->load(mb::kOffSignature) != mb::kSignature)
        return fmt::format("{} was overwritten by another process (its mailbox header is gone)",
                           path_);
    return {};
}

void ShmServer::give_up(const std::string& damage) {
    lost_ = true;
    log(Level::kError,
        "{}: its mapping is gone, so the daemon no longer serves the dual-port RAM file (the "
        "socket still serves); restart the daemon to serve the file again",
        damage);
    // Hosts that map what is left of the file see a board that stopped. The
    // mapping no longer reaches the file: write through the descriptor, and
    // only where the file still has the word (never lengthen it).
    struct stat st {};
    const auto stopped = static_cast<std::uint32_t>(mb::BoardState::kStopped);
    if (::fstat(fd_, &st) == 0 &&
        st.st_size >= static_cast<off_t>(mb::kOffBoardState + sizeof stopped) &&
        ::pwrite(fd_, &stopped, sizeof stopped, mb::kOffBoardState) !=
            static_cast<ssize_t>(sizeof stopped))
        log(Level::kWarn, "{}: cannot mark the board stopped: {}", path_, std::strerror(errno));
}

void ShmServer::serve_loop() {
    mb::Request request;
    std::vector<std::uint8_t> reply;
    request.frame.reserve(mb::kRecordCapacity);
    reply.reserve(mb::kRecordCapacity);
    std::chrono::milliseconds sleep = kFirstSleep;
    mb::AdaptiveSpin spin(kShortestSpin, kLongestSpin);
    rwmos::Host sender;
    std::uint32_t sender_token = 0;
    while (!stop_.load(std::memory_order_relaxed)) {
        if (guard_->lost()) return give_up(damage());
        if (!mb::take_request(*window_, request, spin, sleep)) {
            sleep = std::min(sleep * 2, kLongestSleep);
            // Idle: notice a file shrunk or overwritten before a request runs into it.
            if (std::string bad = damage(); !bad.empty()) return give_up(bad);
            continue;
        }
        // A request read from a file that shrank meanwhile is zeros: not served.
        if (guard_->lost()) return give_up(damage());
        sleep = kFirstSleep;
        reply.clear();
        // The host in this exchange holds the host lock; its token is its pid (docs/dpram.md).
        // Looked up in /proc only when another host's turn comes, not once per request, and
        // for each MotionClaim request, which may record the sender as the holder with its
        // start time: a process that got a dead host's pid since is recorded as itself, not
        // as the dead one (whose start time would end its claim at once).
        const std::uint32_t token = window_->load(mb::kOffHostLock);
        const bool claim_request =
            request.frame.size() >= objif::kFrameHeaderSize &&
            objif::load_little<std::uint16_t>(request.frame.data() + 6) ==
                static_cast<std::uint16_t>(objif::Opcode::kMotionClaim);
        if (token != sender_token || claim_request) {
            sender = mailbox_host(token);
            sender_token = token;
        }
        host_.serve_frame(request.frame, sender, reply);
        mb::put_reply(*window_, request, reply);
    }
}

void ShmServer::stop() {
    if (!window_) return;
    stop_ = true;
    mb::wake_board(*window_);
    if (thread_.joinable()) thread_.join();
    if (!lost_) mb::set_board_state(*window_, mb::BoardState::kStopped);
    window_.reset();
    guard_.reset();  // unguarded before it is unmapped
    ::munmap(map_, mb::kWindowSize);
    // Removed only if the path still names the file this daemon holds open
    // (its inode cannot have been reused meanwhile): a file put in its place
    // since is someone else's.
    struct stat st {};
    if (::lstat(path_.c_str(), &st) == 0) {
        if (st.st_dev == dev_ && st.st_ino == ino_)
            ::unlink(path_.c_str());
        else
            log(Level::kWarn, "{} is no longer the file this daemon served: left in place", path_);
    }
    ::close(fd_);  // releases the lock
    fd_ = -1;
}

}  // namespace rwmos_emu
