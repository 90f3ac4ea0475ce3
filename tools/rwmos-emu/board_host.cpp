// SPDX-License-Identifier: MIT
#include "board_host.h"

#include <algorithm>

#include "rwmos/board_state.h"
#include "rwmos/motion_wire.h"

namespace rwmos_emu {

void BoardTurns::lock() {
    std::unique_lock lock(mutex_);
    const std::uint64_t ticket = next_++;
    turn_.wait(lock, [&] { return serving_ == ticket; });
}

void BoardTurns::unlock() {
    {
        const std::lock_guard lock(mutex_);
        ++serving_;
    }
    turn_.notify_all();
}

rwmos::FrameStream::Result BoardHost::serve_turn(rwmos::FrameStream& stream,
                                                 std::vector<std::uint8_t>& replies,
                                                 const rwmos::FrameStream::Turn& turn) {
    const std::lock_guard lock(turns_);
    const std::uint64_t out_of_memory = server_.out_of_memory();
    const auto result = stream.serve(server_, replies, turn);
    counts_.frames += result.frames;
    counts_.rejected += result.rejected + (server_.out_of_memory() - out_of_memory);
    return result;
}

void BoardHost::serve_frame(std::span<const std::uint8_t> request, const rwmos::Host& host,
                            std::vector<std::uint8_t>& reply) {
    const std::lock_guard lock(turns_);
    const std::uint64_t out_of_memory = server_.out_of_memory();
    const objif::FrameError e = server_.serve(request, host, reply);
    ++counts_.frames;
    if (e != objif::FrameError::kNone || server_.out_of_memory() != out_of_memory)
        ++counts_.rejected;
}

bool BoardHost::drop_claim(std::uint64_t key) {
    const std::lock_guard lock(turns_);
    return server_.claim().drop(key);
}

std::uint64_t BoardHost::pace(std::chrono::steady_clock::time_point now) {
    const std::lock_guard lock(turns_);
    const std::int32_t cycle_us = board_.state().interpolation_cycle_us;
    const std::uint64_t board_now =
        rwmos::serve_clock(board_, objif::ClockRequest{objif::ClockMode::kQuery, 0}).now;
    if (!anchored_ || cycle_us != anchor_cycle_us_) {
        anchored_ = true;
        anchor_time_ = now;
        anchor_cycle_ = board_now;
        anchor_cycle_us_ = cycle_us;
        return 0;
    }
    const auto elapsed =
        std::chrono::duration_cast<std::chrono::microseconds>(now - anchor_time_).count();
    const std::uint64_t target = anchor_cycle_ + static_cast<std::uint64_t>(elapsed / cycle_us);
    if (board_now >= target) return 0;
    // At most one request's worth per call, so that a daemon far behind
    // (stopped for a while, say) catches up tick by tick, serving its clients
    // in between.
    const std::uint64_t behind = std::min(target - board_now, objif::kMaxClockCycles);
    return rwmos::serve_clock(board_, objif::ClockRequest{objif::ClockMode::kStep, behind}).ran;
}

ServedCounts BoardHost::counts() const {
    const std::lock_guard lock(turns_);
    return counts_;
}

std::uint64_t BoardHost::out_of_memory() const {
    const std::lock_guard lock(turns_);
    return server_.out_of_memory();
}

}  // namespace rwmos_emu
