// SPDX-License-Identifier: MIT
// The state-machine harness behind fuzz_emulator: it turns bytes into a
// sequence of operations on an emulated board (object reads and writes,
// spooled profiles, direct and SSF commands, clock steps, trace) and checks
// the board's invariants after every step:
//   - no crash (ASan/UBSan watch the run);
//   - ERROR holds only Table 4 bits ([APCI-TC]), STATUS only Table 5 bits;
//   - STATUS ProfMarked of a group is set exactly when that group holds a
//     profile (docs/motion.md section 4);
//   - no profile lost or duplicated: every executed segment belongs to an
//     accepted profile, a profile's own segment (contour, uncompensated,
//     rapid) runs at most once and in spool order, and once the board is idle
//     every accepted profile has a segment (its own, or an approach,
//     transition or departure) unless a direct command, Reset, RESET or Clean
//     discarded it;
//   - axis positions finite, and the board objects (positions, SpoolerFill,
//     SpoolerCapacity) agree with the motion status; fill <= capacity;
//   - the clock never runs backwards and advances by what was asked.
// The board is reached through BoardPort, so a test can plant a bug between
// the harness and the board and see the invariants catch it
// (emulator_harness_test.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "objif/descriptor.h"
#include "objif/status.h"
#include "objif/value.h"
#include "rwmos/board.h"
#include "rwmos/motion/types.h"

namespace fuzz {

// Reads the fuzzer's bytes front to back; past the end every read is 0.
class ByteSource {
public:
    explicit ByteSource(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
    bool empty() const noexcept { return pos_ >= bytes_.size(); }
    std::uint8_t u8() noexcept { return empty() ? 0 : bytes_[pos_++]; }
    std::uint16_t u16() noexcept;
    std::uint32_t u32() noexcept;
    std::uint64_t u64() noexcept;
    // A value in 0..n-1 (n > 0).
    std::uint32_t pick(std::uint32_t n) noexcept { return u8() % n; }

private:
    std::span<const std::uint8_t> bytes_;
    std::size_t pos_ = 0;
};

// The board as the harness drives it. The default forwards to a real Board;
// a test overrides one call to plant a bug.
class BoardPort {
public:
    BoardPort() = default;
    virtual ~BoardPort() = default;
    BoardPort(const BoardPort&) = delete;
    BoardPort& operator=(const BoardPort&) = delete;

    rwmos::EmulatedBoard& board() noexcept { return board_; }

    virtual objif::Status write(objif::Descriptor& d, const objif::Value& v) { return board_.write(d, v); }
    virtual rwmos::motion::MotionResult spool(const rwmos::motion::Profile& p) { return board_.spool(p); }
    virtual rwmos::motion::MotionResult direct(const rwmos::motion::DirectCommand& c) {
        return board_.direct(c);
    }
    virtual rwmos::motion::MotionResult ssf(rwmos::motion::AxisMask axes, std::int32_t command) {
        return board_.ssf(axes, command);
    }
    virtual void step(std::uint64_t cycles) { board_.step(cycles); }
    virtual std::uint64_t run_until_idle(std::uint64_t max_cycles) { return board_.run_until_idle(max_cycles); }

private:
    rwmos::EmulatedBoard board_;
};

// The operations, one byte each, followed by their arguments.
enum class Op : std::uint8_t {
    kWrite = 0,       // object (dictionary row), index, value
    kRead,            // object (dictionary row), index; or a raw address
    kSpool,           // kind, axes, targets, feed, arc axes, centre
    kDirect,          // code, axes, targets, feed
    kSsf,             // axes, command
    kStep,            // cycles
    kRunUntilIdle,    // the most cycles
    kTrace,           // on/off, capacity; or read samples
    kSetUpGroup,      // group, axes, radius, side, STATUS = 1: reaches compensation quickly
    kCount,
};

class EmulatorHarness {
public:
    static constexpr std::size_t kMaxSteps = 64;  // operations per input

    explicit EmulatorHarness(BoardPort& port);

    // Runs the operations the bytes describe, checking every invariant after
    // each. Returns the first broken invariant ("" when all held).
    std::string run(ByteSource& bytes);

    // The kWrite row number of a writable object (for tests that write bytes by hand).
    std::optional<std::uint8_t> row_of(const objif::Address& a);

private:
    void apply(Op op, ByteSource& bytes);
    void write_object(ByteSource& bytes);
    void read_object(ByteSource& bytes);
    void spool(ByteSource& bytes);
    void direct(ByteSource& bytes);
    void ssf(ByteSource& bytes);
    void trace(ByteSource& bytes);
    void set_up_group(ByteSource& bytes);
    void step(std::uint64_t cycles);
    void run_until_idle(std::uint64_t max_cycles);
    void write_tc(std::int32_t device, std::int32_t index, std::int32_t sub, const objif::Value& v);
    void note_write(const objif::Address& a, objif::Status st);
    void note_motion(const rwmos::motion::MotionResult& r);
    void discard_pending();

    // The invariants; each returns "" or what broke.
    std::string check();
    std::string check_registers();
    std::string check_segments();
    std::string check_motion_status();

    BoardPort& port_;
    std::uint32_t next_tag_ = 1;
    std::set<std::uint32_t> accepted_;  // every profile the board accepted
    std::set<std::uint32_t> pending_;   // accepted, not run, not discarded
    std::set<std::uint32_t> ran_;       // profiles whose own segment ran
    std::uint32_t last_ran_ = 0;
    std::uint64_t now_ = 0;             // the clock as last seen
    std::string broken_;                // set by the operations themselves
};

}  // namespace fuzz
