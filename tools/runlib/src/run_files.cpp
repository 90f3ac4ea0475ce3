// SPDX-License-Identifier: MIT
#include "apci/run/run_files.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <limits.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>

#include "quiet_thread.h"

namespace apci::run {

namespace {

// ---- Temporary files removed by a signal that ends the process

// A slot's path is written only while `used` is 0 (the handler skips it) and with the signals
// blocked (DeferSignals); `used` is a lock-free atomic (safe in a handler) stored with release
// after the path, so a handler on any thread never sees half a path.
struct TemporarySlot {
    std::atomic<int> used{0};
    std::array<char, PATH_MAX> path{};
};
static_assert(std::atomic<int>::is_always_lock_free);
std::array<TemporarySlot, detail::kTemporarySlots> g_temporaries;
bool g_handlers_installed = false;

// The first signal's handler removes the files; one that comes meanwhile (the same signal
// again, as `timeout` sends it to the process and then to its group, or another) waits for it.
std::atomic<int> g_cleanup_started{0};
std::atomic<int> g_cleanup_done{0};
static_assert(std::atomic<int>::is_always_lock_free);

// Only async-signal-safe calls: unlink(2), sigaction(2), nanosleep(2), raise(3). The handler
// stays installed until the files are gone: the run's other threads do not block the signals,
// so a second one delivered to another thread while the first is handled would, with the
// default action already back (SA_RESETHAND), end the process before the files are removed.
// Once they are, the default action is put back and the signal raised again; it is blocked in
// the handler (sa_mask), so it ends the process as it would have without the handler as soon
// as the handler returns.
extern "C" void remove_temporaries_and_reraise(int sig) {
    if (g_cleanup_started.exchange(1) == 0) {
        for (TemporarySlot& slot : g_temporaries)
            if (slot.used.load(std::memory_order_acquire) != 0) ::unlink(slot.path.data());
        g_cleanup_done.store(1);
    } else {
        const timespec pause{0, 100'000};
        while (g_cleanup_done.load() == 0) ::nanosleep(&pause, nullptr);
    }
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    ::sigaction(sig, &default_action, nullptr);
    ::raise(sig);
}

// Every signal whose default action ends the process and that can be caught (Linux).
constexpr std::array kTerminatingSignals{SIGHUP,  SIGINT,  SIGQUIT,   SIGILL,  SIGTRAP, SIGABRT,
                                         SIGBUS,  SIGFPE,  SIGUSR1,   SIGSEGV, SIGUSR2, SIGPIPE,
                                         SIGALRM, SIGTERM, SIGSTKFLT, SIGXCPU, SIGXFSZ, SIGVTALRM,
                                         SIGPROF, SIGIO,   SIGPWR,    SIGSYS};

template <typename F>
void for_each_terminating_signal(F&& f) {
    for (const int sig : kTerminatingSignals) f(sig);
    for (int sig = SIGRTMIN; sig <= SIGRTMAX; ++sig) f(sig);  // real-time: default ends too
}

sigset_t cleanup_signal_set() noexcept {
    sigset_t set;
    sigemptyset(&set);
    for_each_terminating_signal([&](int sig) { sigaddset(&set, sig); });
    return set;
}

// Installs the handler for the signals still at their default action (an ignored SIGHUP under
// nohup stays ignored, a handler someone else installed stays).
void install_handlers() {
    if (g_handlers_installed) return;
    g_handlers_installed = true;
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_reraise;
    sigfillset(&action.sa_mask);
    action.sa_flags = 0;  // not SA_RESETHAND: the handler puts the default back itself
    for_each_terminating_signal([&](int sig) {
        struct sigaction old {};
        if (::sigaction(sig, nullptr, &old) != 0) return;
        if ((old.sa_flags & SA_SIGINFO) != 0 || old.sa_handler != SIG_DFL) return;
        ::sigaction(sig, &action, nullptr);
    });
}

// Call with the signals deferred. -1 when every slot is taken or the path is too long.
int remember_temporary(const std::string& path) {
    if (path.size() >= PATH_MAX) return -1;
    for (std::size_t i = 0; i < g_temporaries.size(); ++i) {
        TemporarySlot& slot = g_temporaries[i];
        if (slot.used.load(std::memory_order_relaxed) != 0) continue;
        std::memcpy(slot.path.data(), path.c_str(), path.size() + 1);
        slot.used.store(1, std::memory_order_release);
        return static_cast<int>(i);
    }
    return -1;
}

void forget_temporary(int slot) {
    if (slot >= 0) g_temporaries[static_cast<std::size_t>(slot)].used.store(0);
}

// 16 hex digits, from the kernel's random source (the clock when it has none).
std::string unique_suffix() {
    std::uint64_t value = 0;
    if (::getrandom(&value, sizeof value, GRND_NONBLOCK) != static_cast<ssize_t>(sizeof value))
        value = static_cast<std::uint64_t>(
                    std::chrono::steady_clock::now().time_since_epoch().count()) ^
                (static_cast<std::uint64_t>(::getpid()) << 32);
    return fmt::format("{:016x}", value);
}

}  // namespace

BoundedRead read_bounded(int fd, std::size_t limit, std::string& text, int& error) {
    text.clear();
    constexpr std::size_t kChunk = std::size_t{1} << 16;
    for (;;) {
        // Never more than limit + 1 bytes: one byte past the limit is enough to refuse.
        const std::size_t room = limit + 1 - text.size();
        const std::size_t want = room < kChunk ? room : kChunk;
        const std::size_t old = text.size();
        text.resize(old + want);
        const ssize_t n = ::read(fd, text.data() + old, want);
        if (n < 0) {
            text.resize(old);
            if (errno == EINTR) continue;
            error = errno;
            return BoundedRead::kError;
        }
        text.resize(old + static_cast<std::size_t>(n));
        if (n == 0) return BoundedRead::kOk;
        if (text.size() > limit) return BoundedRead::kTooLarge;
    }
}

namespace detail {

// A file's data made durable (`call`: fdatasync(2)) on a thread of its own, each time it is
// asked, while its writer goes on. An ask made while a sync is under way is served by one more sync
// after it (any number of asks in between: one). finish() waits for the sync under way and ends the
// thread; an ask not begun by then is dropped (the caller syncs the file itself next).
class SyncBehind {
  public:
    SyncBehind(int fd, OutputFile::SyncCall call) : fd_(fd), call_(call) {
        thread_ = exec::quiet_thread("apci-sync", [this] { serve(); });
    }
    ~SyncBehind() { (void)finish(); }
    SyncBehind(const SyncBehind&) = delete;
    SyncBehind& operator=(const SyncBehind&) = delete;

    void ask() {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            asked_ = true;
        }
        wake_.notify_one();
    }
    // The errno of the first sync that failed, else 0.
    int finish() noexcept {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            finishing_ = true;
        }
        wake_.notify_one();
        if (thread_.joinable()) thread_.join();
        return error_;
    }

  private:
    void serve() {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            wake_.wait(lock, [this] { return asked_ || finishing_; });
            if (finishing_) return;
            asked_ = false;
            lock.unlock();
            const int error = call_(fd_) == 0 ? 0 : errno;
            lock.lock();
            if (error_ == 0) error_ = error;
        }
    }

    const int fd_;
    const OutputFile::SyncCall call_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool asked_ = false;
    bool finishing_ = false;
    int error_ = 0;
    std::thread thread_;  // started in the constructor, once the rest is made
};

}  // namespace detail

DeferSignals::DeferSignals() noexcept {
    const sigset_t set = cleanup_signal_set();
    ::sigprocmask(SIG_BLOCK, &set, &saved_);
}

DeferSignals::~DeferSignals() {
    ::sigprocmask(SIG_SETMASK, &saved_, nullptr);
}

OutputFile::OutputFile() = default;

OutputFile::~OutputFile() {
    discard();
}

std::string OutputFile::open(const std::string& target) {
    target_ = target;
    if (target == "-") return attach(STDOUT_FILENO, false);
    namespace fs = std::filesystem;
    // A symbolic link stays a link: the file it names is replaced. A link to something that is
    // not a regular file is written in place through the link, which the kernel follows: the
    // links of /proc (/dev/stdout, /dev/fd/N, a shell's >(...)) name a pipe or a terminal by a
    // text such as "pipe:[1234]" that is no path (resolving it said "No such file or
    // directory").
    std::string final_path = target;
    struct stat st {};
    if (::lstat(target.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
        if (::stat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode))
            return open_in_place(target);
        std::error_code ec;
        const fs::path resolved = fs::weakly_canonical(target, ec);
        if (ec) return ec.message();
        final_path = resolved.string();
    }
    if (::stat(final_path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) return std::strerror(EISDIR);
        if (!S_ISREG(st.st_mode)) return open_in_place(final_path);
        // A file we may not write is not replaced either.
        if (::access(final_path.c_str(), W_OK) != 0) return std::strerror(errno);
    }
    return open_temporary(final_path);
}

std::string OutputFile::open_in_place(const std::string& path) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return std::strerror(errno);
    final_ = path;
    return attach(fd, true);
}

std::string OutputFile::open_temporary(const std::string& final_path) {
    namespace fs = std::filesystem;
    const fs::path p(final_path);
    const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
    const std::string base = p.filename().string();
    install_handlers();  // before the first temporary file exists
    constexpr int kAttempts = 64;
    for (int attempt = 0; attempt < kAttempts; ++attempt) {
        std::string name = fmt::format("{}/.{}.apcictl-{}", dir, base, unique_suffix());
        int fd = -1;
        int slot = -1;
        {
            const DeferSignals defer;
            // 0666 less the umask (and a default ACL): the mode of any new file.
            fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd >= 0) {
                slot = remember_temporary(name);
                if (slot < 0) {
                    ::unlink(name.c_str());
                    ::close(fd);
                    return "too many temporary files at once";
                }
            }
        }
        if (fd < 0) {
            if (errno == EEXIST) continue;
            return std::strerror(errno);
        }
        final_ = final_path;
        temp_ = std::move(name);
        slot_ = slot;
        return attach(fd, true);
    }
    return "cannot find an unused temporary file name";
}

std::string OutputFile::attach(int fd, bool owns_fd) {
    fd_ = fd;
    owns_fd_ = owns_fd;
    const cookie_io_functions_t io{nullptr, &OutputFile::cookie_write, nullptr,
                                   &OutputFile::cookie_close};
    file_ = ::fopencookie(this, "w", io);
    if (file_ == nullptr) {
        const int e = errno;
        discard();
        return std::strerror(e);
    }
    // Large writes: the writers gather 1 MiB (TextSink) and hand it over in one piece; the
    // FILE passes each piece straight to one write(2) instead of cutting it into its own.
    std::setvbuf(file_, nullptr, _IONBF, 0);
    return {};
}

ssize_t OutputFile::cookie_write(void* cookie, const char* data, std::size_t size) {
    auto* self = static_cast<OutputFile*>(cookie);
    if (!self->replaced_held_) {
        self->replaced_held_ = true;
        self->hold_replaced();
    }
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::write(self->fd_, data + done, size - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (self->write_error_ == 0) self->write_error_ = n < 0 ? errno : ENOSPC;
            errno = self->write_error_;
            // The FILE reads a short count as an error; what was written stays counted.
            return static_cast<ssize_t>(done);
        }
        done += static_cast<std::size_t>(n);
    }
    self->start_writeback(done);
    return static_cast<ssize_t>(done);
}

// The file publish() will replace is read no more: its cached pages are dropped now, on the
// thread that writes (the writer thread of `apcictl run`), rather than freed by the rename at
// the end, which then has less to do (docs/performance.md). It is held open from here on, so
// that the rename frees nothing at all: its blocks are freed where its last descriptor closes
// (release_replaced()). Its contents stay as they are, on the disk; only a regular file is
// touched, opened for reading without following a link.
void OutputFile::hold_replaced() noexcept {
    if (temp_.empty()) return;
    const int fd =
        ::open(final_.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return;  // none yet, or not ours to open
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
        (void)::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
        replaced_fd_ = fd;
        return;
    }
    ::close(fd);
}

// The replaced file's descriptor goes: after the rename (published) on a thread of its own,
// where the kernel frees the file's blocks while the caller goes on (it would have in the
// rename; the caller tears down and ends meanwhile); else at once (the file was not replaced:
// closing it frees nothing).
void OutputFile::release_replaced(bool published) noexcept {
    if (replaced_fd_ < 0) return;
    const int fd = std::exchange(replaced_fd_, -1);
    if (published) {
        try {
            exec::quiet_thread("apci-release", [fd] { ::close(fd); }).detach();
            return;
        } catch (...) {  // no thread: closed here, as the rename would have freed it
        }
    }
    ::close(fd);
}

// A temporary file's pages go to the disk while the run goes on (SYNC_FILE_RANGE_WRITE starts
// the write-back and does not wait for it), so the fsync at close() waits for the last piece
// only. A failure here is not one of the output's: fsync reports what did not reach the disk.
// Every kSyncStep bytes, what was written is also made durable behind the writer
// (sync_behind()).
void OutputFile::start_writeback(std::size_t bytes) noexcept {
    written_ += static_cast<off_t>(bytes);
    if (temp_.empty() || written_ - writeback_from_ < kWritebackStep) return;
    (void)::sync_file_range(fd_, writeback_from_, written_ - writeback_from_,
                            SYNC_FILE_RANGE_WRITE);
    writeback_from_ = written_;
    if (written_ - synced_from_ >= kSyncStep) {
        sync_behind();
        synced_from_ = written_;
    }
}

// The write-back above leaves the data in the disk's cache, and the fsync at close() flushes
// that cache: on a virtual disk whose cache is the host's, the flush takes a time that grows
// with the data it holds (about 0.5 ms per MiB here), all of it at the run's end, which nothing
// else overlaps. A sync on a thread of its own (made at the first step) flushes each step while
// the run goes on; the fsync at close() has the last step left. Where no thread can be made,
// nothing is synced behind: the fsync at close() does it all, as without it.
void OutputFile::sync_behind() noexcept {
    if (sync_unavailable_) return;
    try {
        if (!sync_)
            sync_ = std::make_unique<detail::SyncBehind>(
                fd_, sync_call_ != nullptr ? sync_call_ : &::fdatasync);
        sync_->ask();
    } catch (...) {
        sync_unavailable_ = true;
    }
}

// Waits for the sync behind the writer, if any, and ends its thread: the errno of the first
// of its syncs that failed (what it could not make durable), else 0.
int OutputFile::end_sync_behind() noexcept {
    if (!sync_) return 0;
    const int error = sync_->finish();
    sync_.reset();
    return error;
}

int OutputFile::cookie_close(void* cookie) {
    auto* self = static_cast<OutputFile*>(cookie);
    if (!self->owns_fd_ || self->fd_ < 0) return 0;
    const int fd = self->fd_;
    self->fd_ = -1;
    return ::close(fd);
}

std::string OutputFile::close() {
    if (file_ == nullptr) return {};
    int error = 0;
    if (std::fflush(file_) != 0) error = write_error_ != 0 ? write_error_ : errno;
    // A sync behind the writer that failed reports it here: the fsync below would not (an
    // error is reported once per open file).
    const int behind = end_sync_behind();
    if (error == 0) error = behind;
    // What the kernel could not place yet (delayed allocation, NFS) fails here.
    if (error == 0 && !temp_.empty() && ::fsync(fd_) != 0) error = errno;
    std::FILE* f = file_;
    file_ = nullptr;
    if (std::fclose(f) != 0 && error == 0) error = write_error_ != 0 ? write_error_ : errno;
    if (error == 0 && write_error_ != 0) error = write_error_;
    return error == 0 ? std::string() : std::strerror(error);
}

std::string OutputFile::publish() {
    if (temp_.empty()) return {};
    const DeferSignals defer;
    if (::rename(temp_.c_str(), final_.c_str()) != 0) return std::strerror(errno);
    forget_temporary(slot_);
    slot_ = -1;
    temp_.clear();
    release_replaced(true);
    return {};
}

void OutputFile::discard() noexcept {
    release_replaced(false);
    (void)end_sync_behind();  // before the descriptor it syncs is closed
    if (file_ != nullptr) {
        std::fclose(file_);
        file_ = nullptr;
    }
    if (!temp_.empty()) {
        const DeferSignals defer;
        ::unlink(temp_.c_str());
        forget_temporary(slot_);
        slot_ = -1;
        temp_.clear();
    }
}

bool same_file(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path pa = fs::absolute(a, ec).lexically_normal();
    const fs::path pb = fs::absolute(b, ec).lexically_normal();
    if (pa == pb) return true;
    const fs::path ca = fs::weakly_canonical(pa, ec);
    const bool resolved_a = !ec;
    const fs::path cb = fs::weakly_canonical(pb, ec);
    if (resolved_a && !ec && ca == cb) return true;
    const bool equivalent = fs::equivalent(pa, pb, ec);
    return !ec && equivalent;
}

}  // namespace apci::run
