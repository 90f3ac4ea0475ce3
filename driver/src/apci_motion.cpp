// SPDX-License-Identifier: MIT
// The C API's motion calls (apci.h "Motion"): argument checks, the request
// through the board's Transport, the reply into the caller's structs, the
// last-error text. Like apci.cpp: noexcept, statuses only.
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "apci/apci.h"
#include "c_api.h"
#include "objif/frame.h"

namespace {

using apci::fail;
using objif::Status;

static_assert(APCI_AXIS_COUNT == objif::kWireAxisCount);
static_assert(APCI_SSF_RELEASE_HELD_PROFILE == 2001);
static_assert(APCI_MOTION_IDLE == objif::kClockIdle && APCI_MOTION_HELD == objif::kClockHeld &&
              APCI_MOTION_PROFILE_HELD == objif::kClockProfileHeld &&
              APCI_MOTION_TRACING == objif::kClockTracing);

constexpr const char* kRoleNames[] = {"contour",   "transition",    "approach",
                                      "departure", "uncompensated", "rapid"};

// The board and the pointers a call needs are there; records why not.
bool have(apci_board* board, const char* op, apci_status& status) noexcept {
    if (board != nullptr) return true;
    status = fail(nullptr, Status::kInvalidArgument,
                  [&] { return fmt::format("{}: board is NULL", op); });
    return false;
}
bool have(apci_board* board, const void* p, const char* op, const char* what,
          apci_status& status) noexcept {
    if (p != nullptr) return true;
    status = fail(board, Status::kInvalidArgument,
                  [&] { return fmt::format("{}: {} is NULL", op, what); });
    return false;
}

std::string reason(Status s, std::string_view board_says, std::string_view detail) {
    std::string text = fmt::format("{} ({})", objif::status_name(s), objif::status_message(s));
    if (!board_says.empty()) text += fmt::format(": {}", board_says);
    if (!detail.empty()) text += fmt::format(": {}", detail);
    return text;
}

apci_status done(apci_board* board) noexcept {
    board->last_error.clear();
    board->board_message.clear();
    return APCI_OK;
}

// A spool / direct / ssf reply: its status, the result fields, the text.
// `what` names the call ("spool G01 N60"); it is made only when the call failed, since a
// successful spool is the hot path of `apcictl run`.
template <typename What>
apci_status motion_outcome(apci_board* board, Status s, const objif::MotionReply& rep,
                           apci_motion_result* result, const What& what) noexcept {
    if (result != nullptr) *result = apci_motion_result{rep.group, rep.errors, rep.tag};
    if (objif::ok(s)) return done(board);
    const apci_status st = fail(board, s, [&] {
        std::string text = fmt::format("{}: {}", what(),
                                       reason(s, rep.message, board->transport->failure_detail()));
        if (rep.errors != 0)
            text += fmt::format(" (TC group {} ERROR bits 0x{:02x}, block {})", rep.group,
                                rep.errors, rep.tag);
        return text;
    });
    apci::record(board->board_message, rep.message);
    return st;
}

const char* kind_name(std::uint8_t kind) noexcept {
    static constexpr const char* kNames[] = {"G00", "G01", "G02", "G03"};
    return kind < 4 ? kNames[kind] : "G??";
}

void fill_status(const objif::ClockReply& rep, apci_motion_status* out) noexcept {
    if (out == nullptr) return;
    apci_motion_status s{};
    s.now = rep.now;
    s.ran = rep.ran;
    s.flags = rep.flags;
    s.fill = rep.fill;
    s.capacity = rep.capacity;
    s.compensating_group = rep.compensating_group;
    s.trace_pending = rep.trace_pending;
    s.trace_lost = rep.trace_lost;
    s.segments_pending = rep.segments_pending;
    s.segments_lost = rep.segments_lost;
    std::copy(rep.position.begin(), rep.position.end(), s.position);
    *out = s;
}

// Why the board refused a trace ring, in words: the wire's Clock reply carries a status only.
std::string clock_refusal(const objif::ClockRequest& req, Status s) {
    if (req.mode != objif::ClockMode::kTraceOn) return {};
    constexpr double kSampleBytes = 8.0 * (1 + APCI_AXIS_COUNT);  // a cycle and the axes
    if (s == Status::kNoMemory)
        return fmt::format(
            "a trace ring of {} samples ({:.1f} MiB) is more memory than the board gives its "
            "trace (a daemon's rwmos-emu --trace-memory, 64 MiB unless set); ask for fewer "
            "samples and read them more often",
            req.cycles, static_cast<double>(req.cycles) * kSampleBytes / (1 << 20));
    if (s == Status::kValueTooHigh)
        return fmt::format("a trace ring of {} samples; at most 2^24 (16777216)", req.cycles);
    return {};
}

apci_status clock_call(apci_board* board, objif::ClockRequest req, apci_motion_status* status,
                       const char* op, objif::ClockReply* reply_out = nullptr) noexcept {
    apci_status st = APCI_OK;
    if (!have(board, op, st)) return st;
    try {
        objif::ClockReply rep;
        const Status s = board->transport->clock(req, rep);
        if (!objif::ok(s)) {
            return fail(board, s, [&] {
                return fmt::format(
                    "{}: {}", op,
                    reason(s, clock_refusal(req, s), apci::failure_words(board, s)));
            });
        }
        fill_status(rep, status);
        if (reply_out != nullptr) *reply_out = rep;
        return done(board);
    } catch (...) {
        return fail(board, Status::kNoMemory, [&] { return fmt::format("{}: out of memory", op); });
    }
}

// Reads up to `max` items of `what` in as many requests as it takes.
template <class Out>
apci_status read_items(apci_board* board, objif::TraceKind what, Out* out, std::size_t max,
                       std::size_t* count, const char* op) noexcept {
    apci_status st = APCI_OK;
    if (!have(board, op, st) || !have(board, count, op, "count", st)) return st;
    if (max > 0 && !have(board, out, op, "out", st)) return st;
    try {
        std::size_t got = 0;
        if constexpr (std::is_same_v<Out, apci_segment>) {
            // Straight into `out` where the transport can (inproc); else through read_trace.
            std::size_t n = 0;
            const Status s = board->transport->read_segments(out, max, n);
            if (s != Status::kNotSupported) {
                *count = n;
                if (objif::ok(s)) return done(board);
                return fail(board, s, [&] {
                    return fmt::format("{}: {}", op,
                                       reason(s, {}, apci::failure_words(board, s)));
                });
            }
        }
        while (got < max) {
            const std::size_t want = std::min<std::size_t>(max - got, 0xFFFFFFFFu);
            objif::TraceReply rep;
            const Status s = board->transport->read_trace(
                objif::TraceRequest{what, static_cast<std::uint32_t>(want)}, rep);
            if (!objif::ok(s)) {
                *count = got;  // what was read so far is the caller's now
                return fail(board, s, [&] {
                    return fmt::format("{}: {}", op,
                                       reason(s, {}, apci::failure_words(board, s)));
                });
            }
            std::size_t n = 0;
            if constexpr (std::is_same_v<Out, apci_trace_sample>) {
                n = std::min(rep.samples.size(), max - got);
                for (std::size_t i = 0; i < n; ++i) {
                    out[got + i].cycle = rep.samples[i].cycle;
                    std::copy(rep.samples[i].position.begin(), rep.samples[i].position.end(),
                              out[got + i].position);
                }
            } else {
                n = std::min(rep.segments.size(), max - got);
                for (std::size_t i = 0; i < n; ++i)
                    apci::segment_to_c(rep.segments[i], out[got + i]);
            }
            got += n;
            if (n == 0) break;
        }
        *count = got;
        return done(board);
    } catch (...) {
        return fail(board, Status::kNoMemory, [&] { return fmt::format("{}: out of memory", op); });
    }
}

// Step and RunUntilIdle in requests of at most objif::kMaxClockCycles each
// (the board's per-request bound, which lets a daemon serve its other clients
// in between); `ran` in the status is the sum. Stops at the first failure.
apci_status clock_run(apci_board* board, objif::ClockMode mode, std::uint64_t cycles,
                      apci_motion_status* status, const char* op) noexcept {
    std::uint64_t ran = 0;
    for (;;) {
        const std::uint64_t chunk = std::min(cycles - ran, objif::kMaxClockCycles);
        objif::ClockReply rep;
        const apci_status st = clock_call(board, {mode, chunk}, nullptr, op, &rep);
        if (st != APCI_OK) return st;
        ran += rep.ran;
        const bool idle = (rep.flags & objif::kClockIdle) != 0;
        if (ran == cycles || (mode == objif::ClockMode::kRunUntilIdle && (idle || rep.ran < chunk))) {
            rep.ran = ran;
            fill_status(rep, status);
            return st;
        }
    }
}

}  // namespace

extern "C" {

apci_status apci_spool_profile(apci_board* board, const apci_profile* profile,
                               apci_motion_result* result) noexcept {
    constexpr const char* op = "apci_spool_profile";
    apci_status st = APCI_OK;
    if (!have(board, op, st) || !have(board, profile, op, "profile", st)) return st;
    try {
        objif::SpoolRequest req;
        req.kind = profile->kind;
        req.axes = profile->axes;
        req.arc_axes = {profile->arc_axes[0], profile->arc_axes[1]};
        req.tag = profile->tag;
        req.feed = profile->feed;
        std::copy(profile->target, profile->target + APCI_AXIS_COUNT, req.target.begin());
        req.center = {profile->center[0], profile->center[1]};
        objif::MotionReply rep;
        const Status s = board->transport->spool(req, rep);
        return motion_outcome(board, s, rep, result, [&] {
            return fmt::format("spool {} N{}", kind_name(profile->kind), profile->tag);
        });
    } catch (...) {
        return fail(board, Status::kNoMemory, [&] { return fmt::format("{}: out of memory", op); });
    }
}

apci_status apci_direct_command_send(apci_board* board,
                                     const apci_direct_command* command) noexcept {
    constexpr const char* op = "apci_direct_command_send";
    apci_status st = APCI_OK;
    if (!have(board, op, st) || !have(board, command, op, "command", st)) return st;
    try {
        objif::DirectRequest req;
        req.code = command->code;
        req.axes = command->axes;
        req.feed = command->feed;
        std::copy(command->target, command->target + APCI_AXIS_COUNT, req.target.begin());
        objif::MotionReply rep;
        const Status s = board->transport->direct(req, rep);
        const char* name = command->code == APCI_DIRECT_JA   ? "JA"
                           : command->code == APCI_DIRECT_JS ? "JS"
                                                             : "?";
        return motion_outcome(board, s, rep, nullptr, [&] { return fmt::format("direct {}", name); });
    } catch (...) {
        return fail(board, Status::kNoMemory, [&] { return fmt::format("{}: out of memory", op); });
    }
}

apci_status apci_ssf_command(apci_board* board, uint8_t axes, int32_t command,
                             apci_motion_result* result) noexcept {
    constexpr const char* op = "apci_ssf_command";
    apci_status st = APCI_OK;
    if (!have(board, op, st)) return st;
    try {
        objif::MotionReply rep;
        const Status s = board->transport->ssf(objif::SsfRequest{axes, command}, rep);
        return motion_outcome(board, s, rep, result, [&] {
            return fmt::format("ssf {} to axes 0x{:02x}", command, axes);
        });
    } catch (...) {
        return fail(board, Status::kNoMemory, [&] { return fmt::format("{}: out of memory", op); });
    }
}

apci_status apci_step(apci_board* board, uint64_t cycles, apci_motion_status* status) noexcept {
    return clock_run(board, objif::ClockMode::kStep, cycles, status, "apci_step");
}

apci_status apci_run_until_idle(apci_board* board, uint64_t max_cycles,
                                apci_motion_status* status) noexcept {
    return clock_run(board, objif::ClockMode::kRunUntilIdle, max_cycles, status,
                     "apci_run_until_idle");
}

apci_status apci_motion_status_get(apci_board* board, apci_motion_status* status) noexcept {
    constexpr const char* op = "apci_motion_status_get";
    apci_status st = APCI_OK;
    if (!have(board, op, st) || !have(board, status, op, "status", st)) return st;
    return clock_call(board, {objif::ClockMode::kQuery, 0}, status, op);
}

apci_status apci_spooler_fill(apci_board* board, uint32_t* fill, uint32_t* capacity) noexcept {
    constexpr const char* op = "apci_spooler_fill";
    apci_status st = APCI_OK;
    if (!have(board, op, st) || !have(board, fill, op, "fill", st) ||
        !have(board, capacity, op, "capacity", st))
        return st;
    objif::ClockReply rep;
    st = clock_call(board, {objif::ClockMode::kQuery, 0}, nullptr, op, &rep);
    if (st != APCI_OK) return st;
    *fill = rep.fill;
    *capacity = rep.capacity;
    return APCI_OK;
}

apci_status apci_trace_enable(apci_board* board, uint32_t capacity) noexcept {
    const objif::ClockRequest req = capacity == 0
                                        ? objif::ClockRequest{objif::ClockMode::kTraceOff, 0}
                                        : objif::ClockRequest{objif::ClockMode::kTraceOn, capacity};
    return clock_call(board, req, nullptr, "apci_trace_enable");
}

apci_status apci_read_trace(apci_board* board, apci_trace_sample* out, size_t max,
                            size_t* count) noexcept {
    return read_items(board, objif::TraceKind::kSamples, out, max, count, "apci_read_trace");
}

apci_status apci_read_segments(apci_board* board, apci_segment* out, size_t max,
                               size_t* count) noexcept {
    return read_items(board, objif::TraceKind::kSegments, out, max, count, "apci_read_segments");
}

const char* apci_segment_role_name(int role) noexcept {
    if (role < 0 || role >= static_cast<int>(std::size(kRoleNames))) return nullptr;
    return kRoleNames[role];
}

}  // extern "C"
