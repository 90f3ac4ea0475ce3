// SPDX-License-Identifier: MIT
// The state-machine fuzzer's invariants are real checks: each test plants
// one bug between the harness and the board and runs a short, readable
// operation sequence; the honest board passes the same sequence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "emulator_harness.h"
#include "rwmos/board_state.h"
#include "rwmos/object_map.h"
#include "objif/map/tc_bits.h"

namespace {

namespace motion = rwmos::motion;
namespace tc = rwmos::tc;
using fuzz::Op;

// Writes operations in the harness's byte encoding (emulator_harness.cpp).
class Script {
public:
    // Group 1: axes 0/1, tool 0, radius 1, left, STATUS = 1.
    Script& set_up_group_1() { return op(Op::kSetUpGroup).byte(0).byte(0).byte(1).byte(0); }
    // G01 in X/Y to (x, y) (half units) at F600.
    Script& line(double x, double y) {
        op(Op::kSpool).byte(0).byte(1);  // interpolation kind: G01
        byte(0);                         // axes 0x03
        coordinate(x).coordinate(y);
        return byte(2);                  // F600
    }
    // Writes a small int to row `row` (EmulatorHarness::row_of) at Index first + `index`.
    Script& write(std::uint8_t row, std::uint8_t index, std::int8_t value) {
        return op(Op::kWrite).byte(row).byte(index).byte(0).byte(1).byte(static_cast<std::uint8_t>(value));
    }
    Script& step(std::uint16_t cycles) {
        return op(Op::kStep).byte(static_cast<std::uint8_t>(cycles)).byte(static_cast<std::uint8_t>(cycles >> 8));
    }
    Script& run_until_idle() { return op(Op::kRunUntilIdle).byte(0x40).byte(0x42).byte(0x0F).byte(0); }
    const std::vector<std::uint8_t>& bytes() const { return bytes_; }

private:
    Script& op(Op o) { return byte(static_cast<std::uint8_t>(o)); }
    Script& byte(std::uint8_t b) {
        bytes_.push_back(b);
        return *this;
    }
    Script& coordinate(double v) { return byte(0).byte(static_cast<std::uint8_t>(static_cast<std::int8_t>(v * 2))); }
    std::vector<std::uint8_t> bytes_;
};

std::uint8_t status_row(fuzz::EmulatorHarness& h, std::int32_t group) {
    const auto row = h.row_of({tc::kBus, tc::kDevGroups, group, tc::kSubStatus});
    EXPECT_TRUE(row.has_value());
    return row.value_or(0);
}

// A square, uncompensated, run to the end.
Script square() {
    Script s;
    s.line(10, 0).line(10, 10).line(0, 10).line(0, 0).run_until_idle();
    return s;
}

// The same square compensated by group 1, ended by STATUS = 0.
Script compensated_square(fuzz::EmulatorHarness& h) {
    Script s;
    s.set_up_group_1().line(10, 0).line(10, 10).line(0, 10).line(0, 0).step(100);
    s.write(status_row(h, 1), 1, 0).run_until_idle();
    return s;
}

std::string run(fuzz::BoardPort& port, Script (*make)(fuzz::EmulatorHarness&)) {
    fuzz::EmulatorHarness harness(port);
    const Script script = make(harness);
    fuzz::ByteSource bytes(script.bytes());
    return harness.run(bytes);
}
Script square_of(fuzz::EmulatorHarness&) { return square(); }

// ---- planted bugs

class DuplicatingPort final : public fuzz::BoardPort {
    motion::MotionResult spool(const motion::Profile& p) override {
        const auto r = board().spool(p);
        if (r.ok()) (void)board().spool(p);  // the same profile spooled twice
        return r;
    }
};

class DroppingPort final : public fuzz::BoardPort {
    motion::MotionResult spool(const motion::Profile& p) override {
        if (++calls_ % 2 == 0) return {};  // says Ok, spools nothing
        return board().spool(p);
    }
    int calls_ = 0;
};

class StrayErrorBitPort final : public fuzz::BoardPort {
    objif::Status write(objif::Descriptor& d, const objif::Value& v) override {
        const auto st = board().write(d, v);
        board().state().tc.groups[0].error |= 0x40;  // no Table 4 bit
        return st;
    }
};

class ForgetfulProfMarkedPort final : public fuzz::BoardPort {
    motion::MotionResult spool(const motion::Profile& p) override {
        const auto r = board().spool(p);
        for (auto& g : board().state().tc.groups) g.status &= ~tc::kProfMarked;
        return r;
    }
};

class NanPositionPort final : public fuzz::BoardPort {
    std::uint64_t run_until_idle(std::uint64_t max_cycles) override {
        const auto ran = board().run_until_idle(max_cycles);
        board().state().axes[3].position = std::numeric_limits<double>::quiet_NaN();
        return ran;
    }
};

class SkewedClockPort final : public fuzz::BoardPort {
    void step(std::uint64_t cycles) override { board().step(cycles + 1); }
};

TEST(EmulatorHarness, HonestBoardKeepsEveryInvariant) {
    fuzz::BoardPort plain;
    EXPECT_EQ(run(plain, square_of), "");
    fuzz::BoardPort compensated;
    EXPECT_EQ(run(compensated, compensated_square), "");
}

TEST(EmulatorHarness, PlantedDuplicateProfileIsCaught) {
    DuplicatingPort port;
    EXPECT_EQ(run(port, square_of), "no profile runs twice");
}

TEST(EmulatorHarness, PlantedLostProfileIsCaught) {
    DroppingPort port;
    EXPECT_EQ(run(port, square_of), "no profile lost: once idle, every accepted profile has run or was discarded");
}

TEST(EmulatorHarness, PlantedErrorBitOutsideTable4IsCaught) {
    StrayErrorBitPort port;
    EXPECT_EQ(run(port, compensated_square), "ERROR holds only Table 4 bits");
}

TEST(EmulatorHarness, PlantedStatusInconsistentWithTheHeldProfileIsCaught) {
    ForgetfulProfMarkedPort port;
    EXPECT_EQ(run(port, compensated_square), "STATUS ProfMarked is set exactly when the group holds a profile");
}

TEST(EmulatorHarness, PlantedNonFinitePositionIsCaught) {
    NanPositionPort port;
    EXPECT_EQ(run(port, square_of), "axis positions are finite");
}

TEST(EmulatorHarness, PlantedClockSkewIsCaught) {
    SkewedClockPort port;
    EXPECT_EQ(run(port, compensated_square), "the clock advances by exactly the cycles stepped");
}

}  // namespace
