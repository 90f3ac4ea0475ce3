// SPDX-License-Identifier: MIT
// The files of `apcictl run` (docs/apcictl.md, "Outputs"):
//
//  - an output is written to a temporary file beside its target (same directory, a unique
//    hidden name ".NAME.apcictl-XXXXXXXXXXXXXXXX", created with O_EXCL and the mode of any new
//    file) and renamed over the target only when the whole run succeeded; on any error the
//    temporary file is removed and an existing target is left as it was. "-" is standard
//    output; an existing target that is not a regular file (/dev/null, a FIFO) is written in
//    place. A signal that ends the process (SIGTERM, SIGINT, SIGHUP, SIGPIPE, SIGXFSZ, ...)
//    removes the temporary files first, then ends it as the signal would have (SIGKILL cannot
//    be caught: its temporary files stay behind). At the first write, the cached pages of the
//    target the temporary file will replace are dropped (its contents stay as they are) and
//    the target is held open: the rename at the end then frees nothing, and the replaced
//    file's blocks are freed on a thread of their own, while the process goes on (and ends).
//    While it is written, a temporary file's data goes to the disk every 1 MiB and is made
//    durable every 2 MiB on a thread of its own, so that the fsync before the rename has only
//    the last piece left;
//  - a program read from standard input is held in memory, at most kStdinProgramLimit bytes.
#pragma once

#include <sys/types.h>

#include <csignal>
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>

namespace apci::run {

namespace detail {
class SyncBehind;
}  // namespace detail

// The largest program `apcictl run -` reads from standard input (a larger one is a file).
inline constexpr std::size_t kStdinProgramLimit = std::size_t{64} << 20;  // 64 MiB

enum class BoundedRead {
    kOk,        // all of it, in `text`
    kTooLarge,  // more than `limit` bytes: refused after reading limit + 1 of them
    kError,     // read failed: `error` is its errno
};
// Reads `fd` to its end into `text`, refusing more than `limit` bytes.
BoundedRead read_bounded(int fd, std::size_t limit, std::string& text, int& error);

// Whether two paths name the same file, so that an output would overwrite an input or two
// outputs mix: the same path once absolute and normalised, the same after symbolic links along
// the way (a file not yet there in a linked directory), or (both existing) the same device and
// inode, which catches a hard link too.
bool same_file(const std::string& a, const std::string& b);

// Blocks the signals that remove temporary files while it lives (a temporary file is created
// and registered, or renamed and forgotten, as one step; a group of outputs is published
// together). Signals arriving meanwhile are delivered when it ends.
class DeferSignals {
  public:
    DeferSignals() noexcept;
    ~DeferSignals();
    DeferSignals(const DeferSignals&) = delete;
    DeferSignals& operator=(const DeferSignals&) = delete;

  private:
    sigset_t saved_{};
};

// One output of a run. Not copyable or movable (the FILE refers to it).
class OutputFile {
  public:
    OutputFile();
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    // Opens the output for `target` ("-": standard output). Empty on success, else why not
    // (strerror text: "No such file or directory", "Is a directory", "Permission denied").
    std::string open(const std::string& target);
    std::FILE* file() const noexcept { return file_; }
    const std::string& target() const noexcept { return target_; }
    // The temporary file being written; empty for standard output and in-place targets.
    const std::string& temporary() const noexcept { return temp_; }
    bool is_stdout() const noexcept { return target_ == "-"; }

    // Flushes, syncs and closes the file. Empty on success, else why the first write (or the
    // flush, sync or close) failed: "No space left on device".
    std::string close();
    // Renames the (closed) temporary file over the target. Empty on success, else why not.
    // The file it replaced, held open since the first write, is closed on a thread of its own
    // (its blocks freed there: 2 to 4 ms for a file of 13 MB on an ext4 mounted with discard),
    // left to run while the caller goes on: it does nothing else, and a process that ends
    // first ends it after the close (the kernel finishes a close it has begun).
    std::string publish();
    // Closes and removes the temporary file, if any; the target is not touched.
    void discard() noexcept;

    // The call that makes the written data durable behind the writer (fdatasync(2), the
    // default): a test gives one of its own, before the first write, to count the syncs or make
    // one fail. It is called on the sync's own thread.
    using SyncCall = int (*)(int fd);
    void sync_with(SyncCall call) noexcept { sync_call_ = call; }
    // Whether a thread syncs behind the writer (made at the first step, ended by close()).
    bool syncs_behind() const noexcept { return sync_ != nullptr; }

  private:
    static ssize_t cookie_write(void* cookie, const char* data, std::size_t size);
    static int cookie_close(void* cookie);
    void start_writeback(std::size_t bytes) noexcept;
    void sync_behind() noexcept;
    int end_sync_behind() noexcept;
    void hold_replaced() noexcept;
    void release_replaced(bool published) noexcept;
    std::string open_temporary(const std::string& final_path);
    std::string open_in_place(const std::string& path);
    std::string attach(int fd, bool owns_fd);

    std::string target_;
    std::string final_;  // where publish() renames to: the target, a symbolic link followed
    std::string temp_;
    int fd_ = -1;
    bool owns_fd_ = false;
    std::FILE* file_ = nullptr;
    int write_error_ = 0;  // errno of the first failed write
    int slot_ = -1;        // in the signal handler's list of temporary files
    // Write-back started early (start_writeback): bytes written, and where the next range
    // to start begins; started every kWritebackStep bytes (docs/performance.md, "The run's
    // ends": every 1 MiB, the fsync at close() waits for at most that much).
    static constexpr off_t kWritebackStep = off_t{1} << 20;
    off_t written_ = 0;
    off_t writeback_from_ = 0;
    // Made durable behind the writer (sync_behind): every kSyncStep bytes, a thread of its own
    // (made at the first step; none for a smaller file) syncs what was written, so that the
    // fsync at close() has at most that much left to make durable, where a disk's cache flush
    // takes a time that grows with what it holds (docs/performance.md, "The sync behind the
    // writer").
    static constexpr off_t kSyncStep = off_t{2} << 20;
    off_t synced_from_ = 0;
    std::unique_ptr<detail::SyncBehind> sync_;
    SyncCall sync_call_ = nullptr;   // nullptr: fdatasync(2)
    bool sync_unavailable_ = false;  // no thread could be made: close() syncs it all
    // The first write dropped the cached pages of the file publish() replaces, and opened it:
    // replaced_fd_ (-1: none, or not a regular file), closed by discard() where the output is
    // not published, else on a thread of its own after the rename.
    bool replaced_held_ = false;
    int replaced_fd_ = -1;
};

namespace detail {
// The number of temporary files the signal handler can remove at once.
inline constexpr int kTemporarySlots = 8;
}  // namespace detail

}  // namespace apci::run
