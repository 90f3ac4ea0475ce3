// SPDX-License-Identifier: MIT
// A Board with helpers to set up TC objects, spool profiles and read back
// what was executed, shared by the motion rule tests.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "objif/descriptor.h"
#include "objif/value.h"
#include "rwmos/board.h"
#include "rwmos/board_state.h"
#include "rwmos/object_map.h"
#include "objif/map/tc_bits.h"

namespace motion_test {

using objif::Status;
using objif::Value;
using rwmos::motion::AxisVector;
using rwmos::motion::DirectCode;
using rwmos::motion::DirectCommand;
using rwmos::motion::MotionResult;
using rwmos::motion::Profile;
using rwmos::motion::ProfileKind;
using rwmos::motion::Segment;
using rwmos::motion::SegmentKind;
using rwmos::motion::SegmentRole;

inline AxisVector xyz(double x, double y, double z = 0.0) {
    AxisVector v{};
    v[0] = x;
    v[1] = y;
    v[2] = z;
    return v;
}

inline Profile line(std::uint32_t tag, double x, double y, double feed = 600.0) {
    Profile p;
    p.kind = ProfileKind::kLine;
    p.tag = tag;
    p.feed = feed;
    p.axes = 0x03;
    p.target[0] = x;
    p.target[1] = y;
    return p;
}

inline Profile line3(std::uint32_t tag, double x, double y, double z, double feed = 600.0) {
    Profile p = line(tag, x, y, feed);
    p.axes = 0x07;
    p.target[2] = z;
    return p;
}

inline Profile rapid(std::uint32_t tag, double x, double y) {
    Profile p = line(tag, x, y, 0.0);
    p.kind = ProfileKind::kRapid;
    return p;
}

// G02/G03 in the X-Y plane (axes 0, 1) to (x, y) about (cx, cy).
inline Profile arc(std::uint32_t tag, bool ccw, double x, double y, double cx, double cy,
                   double feed = 600.0) {
    Profile p = line(tag, x, y, feed);
    p.kind = ccw ? ProfileKind::kArcCcw : ProfileKind::kArcCw;
    p.arc_axes = {0, 1};
    p.center = {cx, cy};
    return p;
}

// A board and its helpers; usable on its own (several boards in one test)
// and as a fixture (MotionBoard).
struct Rig {
    rwmos::EmulatedBoard board;
    explicit Rig(const rwmos::BoardConfig& config = {}) : board(config) {}

    Status write_int(std::int32_t bus, std::int32_t dev, std::int32_t idx, std::int32_t sub,
                     std::int32_t v) {
        objif::Descriptor d{{bus, dev, idx, sub}, 0};
        return board.write(d, Value::of_int(v));
    }
    Status write_double(std::int32_t bus, std::int32_t dev, std::int32_t idx, std::int32_t sub,
                        double v) {
        objif::Descriptor d{{bus, dev, idx, sub}, 0};
        return board.write(d, Value::of_double(v));
    }
    std::int32_t read_int(std::int32_t bus, std::int32_t dev, std::int32_t idx, std::int32_t sub) {
        objif::Descriptor d{{bus, dev, idx, sub}, 0};
        Value v;
        EXPECT_EQ(board.read(d, objif::ValueType::kInt32, v), Status::kOk);
        return v.as_int();
    }
    double read_double(std::int32_t bus, std::int32_t dev, std::int32_t idx, std::int32_t sub) {
        objif::Descriptor d{{bus, dev, idx, sub}, 0};
        Value v;
        EXPECT_EQ(board.read(d, objif::ValueType::kDouble, v), Status::kOk);
        return v.as_double();
    }

    // Group `g` on axes X=0, Y=1, Z=`z`, tool radius `r`, side left or right
    // ([APCI-TC] section 2.5 sequence), not yet activated.
    void setup_group(double r, bool left = true, std::int32_t g = 1, std::int32_t z = 2) {
        using namespace rwmos::tc;
        ASSERT_EQ(write_int(kBus, kDevGroups, g, kSubReset, 0), Status::kOk);
        ASSERT_EQ(write_int(kBus, kDevGroups, g, kSubXAxis, 0), Status::kOk);
        ASSERT_EQ(write_int(kBus, kDevGroups, g, kSubYAxis, 1), Status::kOk);
        ASSERT_EQ(write_int(kBus, kDevGroups, g, kSubZAxis, z), Status::kOk);
        ASSERT_EQ(write_int(kBus, kDevGroups, g, kSubWkzIndex, 0), Status::kOk);
        ASSERT_EQ(write_double(kBus, kDevGroups, g, kSubRadius, r), Status::kOk);
        ASSERT_EQ(write_int(kBus, kDevGroups, g, left ? kSubLeft : kSubRight, 0), Status::kOk);
    }
    void activate(std::int32_t g = 1) {
        ASSERT_EQ(write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, g, rwmos::tc::kSubStatus, 1),
                  Status::kOk);
    }
    Status deactivate(std::int32_t g = 1) {
        return write_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, g, rwmos::tc::kSubStatus, 0);
    }
    std::int32_t status(std::int32_t g = 1) {
        return read_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, g, rwmos::tc::kSubStatus);
    }
    std::int32_t error(std::int32_t g = 1) {
        return read_int(rwmos::tc::kBus, rwmos::tc::kDevGroups, g, rwmos::tc::kSubError);
    }
    bool prof_marked(std::int32_t g = 1) { return (status(g) & rwmos::tc::kProfMarked) != 0; }
    bool running(std::int32_t g = 1) { return (status(g) & rwmos::tc::kRun) != 0; }

    void spool_ok(const Profile& p) {
        const MotionResult r = board.spool(p);
        ASSERT_EQ(r.status, Status::kOk) << r.message;
    }
    void run() { board.run_until_idle(100'000'000); }
    std::vector<Segment> segments() {
        std::vector<Segment> out(board.motion_status().segments_pending);
        out.resize(board.read_segments(out));
        return out;
    }
    AxisVector position() const { return board.motion_status().position; }
};

class MotionBoard : public ::testing::Test, public Rig {};

}  // namespace motion_test
