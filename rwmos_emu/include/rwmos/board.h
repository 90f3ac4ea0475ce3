// SPDX-License-Identifier: MIT
// The emulated APCI-8001/8008 running RWMOS.ELF: one struct of state behind
// the universal object interface. Every request is checked before it touches
// state; a bad one gets a status code and changes nothing.
// Not thread-safe: one thread at a time (the daemon serialises its clients).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "objif/descriptor.h"
#include "objif/dictionary.h"
#include "objif/status.h"
#include "objif/value.h"
#include "rwmos/motion/types.h"

namespace rwmos {

struct BoardConfig {
    // Firmware option "optionTC" ([APCI-TC], section 1): without it the TC
    // module (bus 1300) does not exist and every access answers NoSuchDevice.
    bool option_tc = true;
    // The OTC module (bus 1330, online tool compensation, docs/design.md section 4; design option,
    // Options bit 0x02): without it every access to bus 1330 answers NoSuchDevice.
    bool option_otc = true;
    // Temperature compensation in tool direction (bus 1320; [SIN-TEMP]: "eine Option, die vorher
    // freigeschaltet werden muß"). Options bit 0x04.
    bool option_temp_comp = true;
    // The most memory the per-cycle trace's ring may take, in bytes (the emulator's own limit,
    // not the firmware's: a daemon shares its memory among its clients). A trace asked for with
    // more samples than fit is refused with NoMemory and changes nothing. Default: no limit
    // beyond kMaxTraceCapacity.
    std::size_t trace_memory = SIZE_MAX;
};

class EmulatedBoard {
public:
    explicit EmulatedBoard(const BoardConfig& config = {});
    ~EmulatedBoard();
    EmulatedBoard(const EmulatedBoard&) = delete;
    EmulatedBoard& operator=(const EmulatedBoard&) = delete;

    objif::Status read(objif::Descriptor& d, objif::ValueType want, objif::Value& out);
    objif::Status write(objif::Descriptor& d, const objif::Value& v);

    // ---- Motion (docs/motion.md). Each call checks its input first: a bad
    // one changes nothing and the result says what was wrong. TC errors set
    // the group's ERROR bits, clear its Run and hold the spooler until ERROR
    // is written; the result names the group, bits and block tag.
    //
    // Spools one profile (G00/G01/G02/G03). kBusy: the queue cannot take the
    // moves it yields; nothing was taken, run the clock and try again.
    motion::MotionResult spool(const motion::Profile& p);
    // A direct command (JA, JS): discards the spooler and the held profile first.
    motion::MotionResult direct(const motion::DirectCommand& c);
    // An SSF command to the axes in `axes` (2001: release the held profile).
    motion::MotionResult ssf(motion::AxisMask axes, std::int32_t command);
    // Advances the interpolation clock by exactly `cycles` cycles (virtual time).
    void step(std::uint64_t cycles);
    // Advances until nothing can move or `max_cycles` ran; returns the cycles run.
    std::uint64_t run_until_idle(std::uint64_t max_cycles);
    motion::MotionStatus motion_status() const noexcept;
    // Per-cycle samples on (ring of `capacity` samples, 1..kMaxTraceCapacity,
    // and at most trace_memory / sizeof(TraceSample) of them: NoMemory) or
    // off. Turning it on or off drops the samples not yet read; a refusal
    // changes nothing.
    objif::Status set_trace(bool on, std::size_t capacity);
    static constexpr std::size_t kMaxTraceCapacity = std::size_t{1} << 24;
    // Moves the oldest samples / executed segments (up to out.size()) into
    // `out` and returns how many; read ones are gone.
    std::size_t read_trace(std::span<motion::TraceSample> out);
    std::size_t read_segments(std::span<motion::Segment> out);
    // The same, the segments handed to visit(run, context) where the log holds them (no copy),
    // oldest first, at most `max`, in at most two runs of consecutive segments; returns how
    // many. visit must not call the board.
    using SegmentVisitor = void (*)(std::span<const motion::Segment> run, void* context);
    std::size_t take_segments(std::size_t max, SegmentVisitor visit, void* context);

    const BoardConfig& config() const noexcept;
    objif::Dictionary& dictionary() noexcept;

    struct State;  // all device state, defined in board_state.h
    // The state behind the objects, for the emulator's own layers (motion,
    // spooler, clock) and for tests; PCAP-style code goes through read/write.
    State& state() noexcept;
    const State& state() const noexcept;

private:
    std::unique_ptr<State> state_;
};

}  // namespace rwmos
