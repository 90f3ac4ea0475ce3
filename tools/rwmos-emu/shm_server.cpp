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
}  // namespace

ShmServer::~ShmServer() {
    stop();
}

bool ShmServer::open(const std::string& path, std::string& why) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0660);
    if (fd < 0) {
        why = fmt::format("{}: {}", path, std::strerror(errno));
        return false;
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        ::close(fd);
        why =
            err == EWOULDBLOCK
                ? fmt::format(
                      "{} is served by another daemon; stop it first or choose another --shm", path)
                : fmt::format("lock {}: {}", path, std::strerror(err));
        return false;
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || ::fchmod(fd, 0660) != 0 ||
        ::ftruncate(fd, static_cast<off_t>(mb::kWindowSize)) != 0) {
        why = S_ISREG(st.st_mode) ? fmt::format("{}: {}", path, std::strerror(errno))
                                  : fmt::format("{} is not a regular file", path);
        ::close(fd);
        return false;
    }
    void* map = ::mmap(nullptr, mb::kWindowSize, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (map == MAP_FAILED) {
        why = fmt::format("mmap {}: {}", path, std::strerror(errno));
        ::close(fd);
        return false;
    }
    fd_ = fd;
    map_ = map;
    path_ = path;
    dev_ = st.st_dev;
    ino_ = st.st_ino;
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

void ShmServer::serve_loop() {
    mb::Request request;
    std::vector<std::uint8_t> reply;
    request.frame.reserve(mb::kRecordCapacity);
    reply.reserve(mb::kRecordCapacity);
    std::chrono::milliseconds sleep = kFirstSleep;
    mb::AdaptiveSpin spin(kShortestSpin, kLongestSpin);
    while (!stop_.load(std::memory_order_relaxed)) {
        if (!mb::take_request(*window_, request, spin, sleep)) {
            sleep = std::min(sleep * 2, kLongestSleep);
            continue;
        }
        sleep = kFirstSleep;
        reply.clear();
        host_.serve_frame(request.frame, reply);
        mb::put_reply(*window_, request, reply);
    }
}

void ShmServer::stop() {
    if (!window_) return;
    stop_ = true;
    mb::wake_board(*window_);
    if (thread_.joinable()) thread_.join();
    mb::set_board_state(*window_, mb::BoardState::kStopped);
    window_.reset();
    ::munmap(map_, mb::kWindowSize);
    struct stat st {};
    if (::lstat(path_.c_str(), &st) == 0 && st.st_dev == dev_ && st.st_ino == ino_)
        ::unlink(path_.c_str());
    ::close(fd_);  // releases the lock
    fd_ = -1;
}

}  // namespace rwmos_emu
