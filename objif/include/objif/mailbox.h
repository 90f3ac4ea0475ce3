// SPDX-License-Identifier: MIT
// The board's dual-port RAM mailbox (docs/design.md section 6, design): the same
// wire frames as every other transport (frame.h), carried through a window of
// 32-bit words that host and board both see. docs/dpram.md is the spec page.
//
//   offset   size     field
//   0x0000   4        signature  0x4D505244 ("DRPM")
//   0x0004   4        layout version 2
//   0x0008   4        window size in bytes (kWindowSize)
//   0x000C   4        record capacity in bytes (kRecordCapacity)
//   0x0010   4        board state: 0 stopped, 1 serving
//   0x0014   4        board generation: incremented each time a board starts serving
//   0x0040   4        host lock: 0 free, else the owning host's token
//   0x0100   4        request sequence: the host's doorbell, one more for each request
//   0x0104   4        board sleeping: 1 while the board waits for the next request
//   0x0108   4 + n    request record: length in bytes, then the request frame
//   0x10200  4        reply sequence: the board's doorbell, the request sequence it answered
//   0x10204  4        host sleeping: 1 while a host waits for the reply
//   0x10208  4 + n    reply record: length in bytes, then the reply frame
//
// A request is pending while the two sequences differ. The host owns the
// request record while they are equal and the board from the host's bump of
// the request sequence until its reply sequence catches up; the reply record
// is the board's until then and the host's after. Every sequence store is a
// release and every sequence load an acquire, so a record is complete before
// its sequence says so. Only 32-bit aligned accesses are made (a PCI I/O BAR
// read through sysfs answers 1, 2 or 4 bytes at a time).
//
// Each side's doorbell shares its 64-byte cache line with the first bytes of
// its record and with the other side's sleeping word, and the words both
// sides read on every exchange (header) or only hosts write (lock) sit on
// lines of their own: an exchange moves the request line to the board and
// the reply line to the host, and nothing else (docs/performance.md).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "objif/adaptive_spin.h"
#include "objif/frame.h"
#include "objif/status.h"

namespace objif::mailbox {

inline constexpr std::uint32_t kSignature = 0x4D505244;  // "DRPM" in little-endian byte order
inline constexpr std::uint32_t kLayoutVersion = 2;

inline constexpr std::size_t kOffSignature = 0x0000;
inline constexpr std::size_t kOffVersion = 0x0004;
inline constexpr std::size_t kOffWindowSize = 0x0008;
inline constexpr std::size_t kOffRecordCapacity = 0x000C;
inline constexpr std::size_t kOffBoardState = 0x0010;
inline constexpr std::size_t kOffGeneration = 0x0014;
inline constexpr std::size_t kOffHostLock = 0x0040;

// One record holds one whole frame of the largest payload, rounded to words.
inline constexpr std::size_t kRecordCapacity = (kFrameOverhead + kMaxPayload + 3) / 4 * 4;
inline constexpr std::size_t kOffRequestSequence = 0x00100;
inline constexpr std::size_t kOffBoardSleeping = 0x00104;
inline constexpr std::size_t kOffRequest = 0x00108;  // length, then the frame
inline constexpr std::size_t kOffReplySequence = 0x10200;
inline constexpr std::size_t kOffHostSleeping = 0x10204;
inline constexpr std::size_t kOffReply = 0x10208;  // length, then the frame
inline constexpr std::size_t kWindowSize = kOffReply + 4 + kRecordCapacity;
static_assert(kOffRequest + 4 + kRecordCapacity <= kOffReplySequence, "records overlap");
static_assert(kWindowSize <= 0x40000, "the window fits a 256 KiB BAR");
static_assert(kOffRequestSequence % 64 == 0 && kOffReplySequence % 64 == 0 &&
                  kOffHostLock % 64 == 0,
              "doorbells and the lock start cache lines of their own");

enum class BoardState : std::uint32_t { kStopped = 0, kServing = 1 };

// How host and board reach the window's words. Implementations: a memory
// mapping (shared-memory file, PCI memory BAR, UIO map) in mailbox.cpp, and
// pread/pwrite on a PCI I/O BAR in the driver. Every method is noexcept and
// blocks no longer than the device access itself, except wait().
class Window {
  public:
    virtual ~Window() = default;

    // 32-bit accesses at a word-aligned offset. load() acquires, store() releases.
    virtual std::uint32_t load(std::size_t offset) noexcept = 0;
    virtual void store(std::size_t offset, std::uint32_t value) noexcept = 0;
    // Sequentially consistent store and load, for the sleeping-flag handshake.
    virtual void store_fence(std::size_t offset, std::uint32_t value) noexcept {
        store(offset, value);
    }
    virtual std::uint32_t load_fence(std::size_t offset) noexcept { return load(offset); }
    // Atomic compare-and-swap where the window can do one; false if not equal.
    virtual bool compare_exchange(std::size_t offset, std::uint32_t expected,
                                  std::uint32_t desired) noexcept = 0;
    // Bulk copies at a word-aligned offset; `size` need not be a multiple of 4.
    virtual void read(std::size_t offset, std::uint8_t* out, std::size_t size) noexcept = 0;
    virtual void write(std::size_t offset, const std::uint8_t* in, std::size_t size) noexcept = 0;

    // Whether wait()/wake() sleep in the kernel (a futex on a shared mapping)
    // or only pace a poll (device memory that the board's firmware updates).
    virtual bool can_sleep() const noexcept { return false; }
    // Sleeps while the word at `offset` equals `expected`, at most `timeout`.
    // Windows that cannot sleep yield the CPU briefly instead.
    virtual void wait(std::size_t offset, std::uint32_t expected,
                      std::chrono::nanoseconds timeout) noexcept;
    // Wakes every waiter on the word at `offset` (no-op if !can_sleep()).
    virtual void wake(std::size_t offset) noexcept { (void)offset; }

    // The first device access error since open ("" if none), and its status.
    // The driver's I/O-BAR window reports errno here; mappings never fail.
    virtual Status error() const noexcept { return Status::kOk; }
    virtual std::string error_text() const { return {}; }
};

// A window on memory mapped into this process (MAP_SHARED): atomics on the
// words, memcpy for the records, futex wait/wake when `can_sleep`.
class MappedWindow : public Window {
  public:
    MappedWindow(void* base, std::size_t size, bool can_sleep) noexcept
        : base_(static_cast<std::uint8_t*>(base)), size_(size), can_sleep_(can_sleep) {}

    std::uint32_t load(std::size_t offset) noexcept override;
    void store(std::size_t offset, std::uint32_t value) noexcept override;
    void store_fence(std::size_t offset, std::uint32_t value) noexcept override;
    std::uint32_t load_fence(std::size_t offset) noexcept override;
    bool compare_exchange(std::size_t offset, std::uint32_t expected,
                          std::uint32_t desired) noexcept override;
    void read(std::size_t offset, std::uint8_t* out, std::size_t size) noexcept override;
    void write(std::size_t offset, const std::uint8_t* in, std::size_t size) noexcept override;
    bool can_sleep() const noexcept override { return can_sleep_; }
    void wait(std::size_t offset, std::uint32_t expected,
              std::chrono::nanoseconds timeout) noexcept override;
    void wake(std::size_t offset) noexcept override;

    std::uint8_t* base() const noexcept { return base_; }
    std::size_t size() const noexcept { return size_; }

  private:
    std::uint8_t* base_;
    std::size_t size_;
    bool can_sleep_;
};

// The spin budget of a waiting side (objif/adaptive_spin.h).
using objif::AdaptiveSpin;

// Why a window is not a usable mailbox, in words; "" when it is.
std::string check_layout(Window& w);

// ---- Board side (the emulator; the firmware on a real board).

// Writes the header of a fresh mailbox (signature, version, sizes, sequences 0,
// lock free) and leaves the board state Stopped.
void format(Window& w);
// Marks the board serving (bumping the generation) or stopped.
void set_board_state(Window& w, BoardState state);

// A request the board took: its frame and the sequence number its reply answers.
struct Request {
    std::vector<std::uint8_t> frame;
    std::uint32_t sequence = 0;
};

// Waits for a request (the request sequence differing from the reply
// sequence). Spins for `spin` first (low latency while a host is busy), then
// sleeps on the request sequence until a request arrives, `timeout` passes,
// or wake_board() is called. Returns true with the request in `request`. A
// request record whose length is out of range is answered by the caller like
// any bad frame: the frame bytes given are then empty.
bool take_request(Window& w, Request& request, std::chrono::nanoseconds spin,
                  std::chrono::nanoseconds timeout);
// The same with a spin budget that learns from each wait.
bool take_request(Window& w, Request& request, AdaptiveSpin& spin,
                  std::chrono::nanoseconds timeout);
// Writes the reply record and the request's sequence as the reply sequence,
// waking a sleeping host.
void put_reply(Window& w, const Request& request, std::span<const std::uint8_t> reply);
// Wakes a board sleeping in take_request (used to stop the serving thread).
void wake_board(Window& w);

// ---- Host side (the driver).

struct HostOptions {
    std::uint32_t token = 1;                // this host's lock token (non-zero)
    std::chrono::nanoseconds spin{20'000};  // spin before sleeping while waiting
    AdaptiveSpin* adaptive = nullptr;       // if set: its budget instead of `spin`, and it learns
    std::chrono::milliseconds timeout{5'000};  // whole exchange
    // Whether a lock held by `token` belongs to a host that is gone (e.g. a
    // dead process); such a lock is taken over. Asked while the lock is not
    // free, with how long this exchange has seen that token hold it, and
    // `holder_context`. Null: never.
    bool (*lock_holder_gone)(std::uint32_t token, std::chrono::nanoseconds held_for,
                             const void* context) = nullptr;
    const void* holder_context = nullptr;
};

// One request/reply exchange: takes the host lock, writes the request, rings
// the request doorbell, waits for the reply doorbell, reads the reply into
// `reply` and frees the lock.
//  kOk; kTimeout (lock not free, or no reply in time: the board may still act
//  on the request); kTransportError (board not serving, window error, reply
//  record out of range) with `why` saying which; kInvalidArgument (request
//  larger than a record).
Status exchange(Window& w, const HostOptions& options, std::span<const std::uint8_t> request,
                std::vector<std::uint8_t>& reply, std::string& why);

}  // namespace objif::mailbox
