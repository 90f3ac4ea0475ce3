// SPDX-License-Identifier: MIT
// apci.hpp - the thin C++ API of libapci: header-only, over apci.h.
//
//   apci::Board board("emu:");                      // RAII: closed by the destructor
//   if (!board) { std::cerr << board.last_error(); }
//   auto radius = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_RADIUS);
//   if (auto r = board.write(radius, 2.5); !r) std::cerr << board.last_error();
//   auto v = board.read_double(radius);             // v.status, v.value
//
// Nothing here throws: results carry the status (apci.h codes) and a value.
// Threading as apci.h: one thread at a time per Board.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "apci/apci.h"

namespace apci {

using Status = apci_status;
using ObjectDescriptor = apci_object_descriptor;

// A descriptor for (bus, device, index, subindex) with an unresolved handle.
constexpr ObjectDescriptor object(std::int32_t bus, std::int32_t device, std::int32_t index,
                                  std::int32_t subindex) noexcept {
    return ObjectDescriptor{bus, device, index, subindex, 0};
}

inline std::string_view status_name(Status s) noexcept { return apci_status_name(s); }
inline std::string_view status_message(Status s) noexcept { return apci_status_message(s); }

namespace detail {
// The words of a C call that writes them as snprintf does (`write(text, size)` returns their
// whole length): asked once for the length, then into a string of that size.
template <class Write>
std::string words_of(Write&& write) {
    std::string text(write(nullptr, 0), '\0');
    if (!text.empty()) (void)write(text.data(), text.size() + 1);
    return text;
}
}  // namespace detail

// Status of one call plus, for reads, the value (meaningful only when ok()).
template <class T>
struct Result {
    Status status = APCI_OK;
    T value{};

    constexpr bool ok() const noexcept { return status == APCI_OK; }
    constexpr explicit operator bool() const noexcept { return ok(); }
    constexpr T value_or(T fallback) const noexcept { return ok() ? value : fallback; }
    std::string_view name() const noexcept { return status_name(status); }
    std::string_view message() const noexcept { return status_message(status); }
};

template <>
struct Result<void> {
    Status status = APCI_OK;

    constexpr bool ok() const noexcept { return status == APCI_OK; }
    constexpr explicit operator bool() const noexcept { return ok(); }
    std::string_view name() const noexcept { return status_name(status); }
    std::string_view message() const noexcept { return status_message(status); }
};

// An open board (apci_board*), closed when the Board is destroyed. Move-only.
class Board {
public:
    // Not open; every access answers APCI_INVALID_ARGUMENT.
    Board() noexcept = default;
    // Opens `uri` (apci_open: nullptr, "" and "emu:" are the embedded
    // emulator). Check is_open() / open_status(); last_error() says why not.
    explicit Board(const char* uri) noexcept {
        open_status_ = apci_open(uri, &handle_);
        if (handle_ == nullptr) keep_open_error(apci_last_error(nullptr));
    }
    explicit Board(const std::string& uri) noexcept : Board(uri.c_str()) {}

    Board(Board&& other) noexcept
        : handle_(std::exchange(other.handle_, nullptr)),
          open_status_(other.open_status_),
          open_error_(std::move(other.open_error_)) {}
    Board& operator=(Board&& other) noexcept {
        if (this != &other) {
            apci_close(handle_);
            handle_ = std::exchange(other.handle_, nullptr);
            open_status_ = other.open_status_;
            open_error_ = std::move(other.open_error_);
        }
        return *this;
    }
    Board(const Board&) = delete;
    Board& operator=(const Board&) = delete;
    ~Board() { apci_close(handle_); }

    bool is_open() const noexcept { return handle_ != nullptr; }
    explicit operator bool() const noexcept { return is_open(); }
    // The status apci_open answered (APCI_NOT_SUPPORTED, ... or APCI_OK).
    Status open_status() const noexcept { return open_status_; }
    // apci_last_error() of this board; why it did not open if it is not open.
    std::string_view last_error() const noexcept {
        return is_open() ? std::string_view(apci_last_error(handle_)) : open_error_;
    }
    // apci_last_board_message(): the board's own reason for refusing the last motion call.
    std::string_view last_board_message() const noexcept {
        return is_open() ? std::string_view(apci_last_board_message(handle_)) : std::string_view();
    }
    apci_board* native_handle() const noexcept { return handle_; }

    // The link (apci.h "The link to the board").
    Result<void> set_timeout(std::uint32_t milliseconds) noexcept {
        return Result<void>{apci_set_timeout(handle_, milliseconds)};
    }
    Result<std::uint32_t> timeout() const noexcept {
        Result<std::uint32_t> r;
        r.status = apci_get_timeout(handle_, &r.value);
        return r;
    }
    bool connected() const noexcept { return apci_is_connected(handle_) != 0; }
    Result<void> reconnect() noexcept { return Result<void>{apci_reconnect(handle_)}; }
    // What ended the link, without what to do about it ("" while it works: apci_link_lost).
    std::string link_lost() const {
        return detail::words_of(
            [&](char* text, std::size_t size) { return apci_link_lost(handle_, text, size); });
    }

    // The board's motion for this handle alone (apci.h "Exclusive use of the board's motion").
    // MotionClaim below holds it for a scope.
    Result<void> claim_motion() noexcept { return Result<void>{apci_claim_motion(handle_)}; }
    Result<void> release_motion() noexcept { return Result<void>{apci_release_motion(handle_)}; }
    Result<apci_motion_claim> motion_claim() noexcept {
        Result<apci_motion_claim> r;
        r.status = apci_motion_claim_get(handle_, &r.value);
        return r;
    }

    Result<std::int32_t> read_int(ObjectDescriptor& o) noexcept {
        Result<std::int32_t> r;
        r.status = apci_read_int(handle_, &o, &r.value);
        return r;
    }
    Result<double> read_double(ObjectDescriptor& o) noexcept {
        Result<double> r;
        r.status = apci_read_double(handle_, &o, &r.value);
        return r;
    }
    // read<std::int32_t>(o) or read<double>(o).
    template <class T>
    Result<T> read(ObjectDescriptor& o) noexcept {
        static_assert(std::is_same_v<T, std::int32_t> || std::is_same_v<T, double>,
                      "objects hold int32 or double");
        if constexpr (std::is_same_v<T, double>) {
            return read_double(o);
        } else {
            return read_int(o);
        }
    }

    Result<void> write_int(ObjectDescriptor& o, std::int32_t v) noexcept {
        return Result<void>{apci_write_int(handle_, &o, v)};
    }
    Result<void> write_double(ObjectDescriptor& o, double v) noexcept {
        return Result<void>{apci_write_double(handle_, &o, v)};
    }
    // The argument's type picks the accessor: write(o, 5) is int, write(o, 2.5) double.
    Result<void> write(ObjectDescriptor& o, std::int32_t v) noexcept { return write_int(o, v); }
    Result<void> write(ObjectDescriptor& o, double v) noexcept { return write_double(o, v); }

    // ---- Motion (apci.h "Motion"; docs/motion.md). The value of a spool or
    // ssf result says which TC group and ERROR bits a TC error set.
    Result<apci_motion_result> spool(const apci_profile& p) noexcept {
        Result<apci_motion_result> r;
        r.status = apci_spool_profile(handle_, &p, &r.value);
        return r;
    }
    Result<void> direct(const apci_direct_command& c) noexcept {
        return Result<void>{apci_direct_command_send(handle_, &c)};
    }
    Result<apci_motion_result> ssf(std::uint8_t axes, std::int32_t command) noexcept {
        Result<apci_motion_result> r;
        r.status = apci_ssf_command(handle_, axes, command, &r.value);
        return r;
    }
    Result<apci_motion_status> step(std::uint64_t cycles) noexcept {
        Result<apci_motion_status> r;
        r.status = apci_step(handle_, cycles, &r.value);
        return r;
    }
    Result<apci_motion_status> run_until_idle(std::uint64_t max_cycles) noexcept {
        Result<apci_motion_status> r;
        r.status = apci_run_until_idle(handle_, max_cycles, &r.value);
        return r;
    }
    Result<apci_motion_status> motion_status() noexcept {
        Result<apci_motion_status> r;
        r.status = apci_motion_status_get(handle_, &r.value);
        return r;
    }
    // capacity 0: per-cycle samples off.
    Result<void> trace_enable(std::uint32_t capacity) noexcept {
        return Result<void>{apci_trace_enable(handle_, capacity)};
    }
    // Reads up to `max` into `out`; the value is how many.
    Result<std::size_t> read_trace(apci_trace_sample* out, std::size_t max) noexcept {
        Result<std::size_t> r;
        r.status = apci_read_trace(handle_, out, max, &r.value);
        return r;
    }
    Result<std::size_t> read_segments(apci_segment* out, std::size_t max) noexcept {
        Result<std::size_t> r;
        r.status = apci_read_segments(handle_, out, max, &r.value);
        return r;
    }

private:
    void keep_open_error(const char* text) noexcept {
        try {
            open_error_ = text;
        } catch (...) {
            open_error_.clear();
        }
    }

    apci_board* handle_ = nullptr;
    Status open_status_ = APCI_INVALID_ARGUMENT;  // "not opened" for a default Board
    std::string open_error_ = "board not open";
};

// Holds the board's motion for a scope, as std::lock_guard holds a mutex: claims it when made
// (check held(); the board's last_error() names the holder when another has it) and releases
// it when destroyed.
class MotionClaim {
public:
    explicit MotionClaim(Board& board) noexcept
        : board_(&board), status_(board.claim_motion().status) {}
    ~MotionClaim() {
        if (held()) (void)board_->release_motion();
    }
    MotionClaim(const MotionClaim&) = delete;
    MotionClaim& operator=(const MotionClaim&) = delete;

    bool held() const noexcept { return status_ == APCI_OK; }
    Status status() const noexcept { return status_; }

private:
    Board* board_;
    Status status_;
};

// The holder's command name in `claim`: its characters up to the NUL, no more than the record
// holds.
inline std::string motion_claim_name(const apci_motion_claim& claim) {
    std::size_t n = 0;
    while (n < sizeof claim.name && claim.name[n] != '\0') ++n;
    return {claim.name, n};
}

// The holder of `claim` named as libapci names it in a refusal (apci_motion_claim_holder):
// "pid 4242 (apcictl) since 2024-05-01 12:00:00 UTC"; "" when nobody holds it.
inline std::string motion_claim_holder(const apci_motion_claim& claim) {
    return detail::words_of([&](char* text, std::size_t size) {
        return apci_motion_claim_holder(&claim, text, size);
    });
}

// A board apci_list_devices() found.
struct FoundBoard {
    std::string uri;
    std::string description;
};

// Every board this machine can reach (apci_list_devices); problems, if any,
// are in apci_last_error(nullptr). Empty if the list cannot be made.
inline std::vector<FoundBoard> list_boards() noexcept {
    std::vector<FoundBoard> found;
    try {
        apci_list_devices(
            [](const char* uri, const char* description, void* user) {
                try {
                    static_cast<std::vector<FoundBoard>*>(user)->push_back({uri, description});
                } catch (...) {
                }
            },
            &found);
    } catch (...) {
    }
    return found;
}

}  // namespace apci
