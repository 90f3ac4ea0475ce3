// SPDX-License-Identifier: MIT
// One conformance suite, run on every transport that can run here: a PCAP
// program must see the same board through the embedded emulator, the daemon
// socket, the dual-port RAM mailbox (shared-memory file, PCI BAR) and USB.
// Every test opens a fresh board through the public C API only and expects
// exactly what the embedded emulator answers: the object interface's check
// order, handles, and the TC module's state rules (docs/design.md sections 2, 3).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "apci/apci.h"
#include "objif/names.h"
#include "board_sources.h"

namespace {

using conformance::BoardSource;
using conformance::Transport;

constexpr std::int32_t kBoardBus = 1000;
constexpr std::int32_t kGroup = APCI_TC_DEVICE_GROUP;
constexpr std::int32_t kInit = APCI_TC_DEVICE_INIT;

apci_object_descriptor object(std::int32_t bus, std::int32_t device, std::int32_t index,
                              std::int32_t sub) {
    return apci_object_descriptor{bus, device, index, sub, 0};
}
apci_object_descriptor tc_init(std::int32_t index, std::int32_t sub = 0) {
    return object(APCI_TC_BUS, kInit, index, sub);
}
apci_object_descriptor tc_group(std::int32_t group, std::int32_t sub) {
    return object(APCI_TC_BUS, kGroup, group, sub);
}
apci_object_descriptor board_object(std::int32_t index, std::int32_t sub = 0) {
    return object(kBoardBus, 0, index, sub);
}
// The address of a temporary, for C calls that take a pointer to const.
template <class T>
const T* ptr(const T& value) {
    return &value;
}

class Conformance : public ::testing::TestWithParam<Transport> {
  protected:
    void SetUp() override { open_board(true); }
    void TearDown() override {
        apci_close(board_);
        board_ = nullptr;
        source_.reset();
    }

    void open_board(bool option_tc) {
        apci_close(board_);
        board_ = nullptr;
        source_.reset();  // before the next one starts: one board at a time
        source_ = GetParam().make(option_tc);
        ASSERT_NE(source_, nullptr) << "could not start a board for " << GetParam().name;
        ASSERT_EQ(apci_open(source_->uri().c_str(), &board_), APCI_OK) << apci_last_error(nullptr);
    }

    apci_status write_int(apci_object_descriptor o, std::int32_t v) {
        return apci_write_int(board_, &o, v);
    }
    apci_status write_double(apci_object_descriptor o, double v) {
        return apci_write_double(board_, &o, v);
    }
    apci_status read_int_status(apci_object_descriptor o) {
        std::int32_t v = 0;
        return apci_read_int(board_, &o, &v);
    }
    apci_status read_double_status(apci_object_descriptor o) {
        double v = 0;
        return apci_read_double(board_, &o, &v);
    }
    std::int32_t read_int(apci_object_descriptor o) {
        std::int32_t v = -12345;
        EXPECT_EQ(apci_read_int(board_, &o, &v), APCI_OK) << apci_last_error(board_);
        return v;
    }
    double read_double(apci_object_descriptor o) {
        double v = -12345.0;
        EXPECT_EQ(apci_read_double(board_, &o, &v), APCI_OK) << apci_last_error(board_);
        return v;
    }

    // docs/design.md section 3, [APCI-TC] section 2.5: axes, tool, radius, side.
    void initialise_group(std::int32_t g) {
        ASSERT_EQ(write_int(tc_group(g, APCI_TC_XAXIS), 0), APCI_OK);
        ASSERT_EQ(write_int(tc_group(g, APCI_TC_YAXIS), 1), APCI_OK);
        ASSERT_EQ(write_int(tc_group(g, APCI_TC_ZAXIS), 2), APCI_OK);
        ASSERT_EQ(write_int(tc_group(g, APCI_TC_WKZINDEX), 1), APCI_OK);
        ASSERT_EQ(write_double(tc_group(g, APCI_TC_RADIUS), 2.0), APCI_OK);
        ASSERT_EQ(write_int(tc_group(g, APCI_TC_RIGHT), 1), APCI_OK);
    }

    std::unique_ptr<BoardSource> source_;
    apci_board* board_ = nullptr;
};

// ---- Object interface

TEST_P(Conformance, BoardModuleAnswersItsConstants) {
    EXPECT_EQ(read_int(board_object(1)), 0x010000) << "FirmwareVersion 1.0.0";
    EXPECT_EQ(read_int(board_object(3)), 8) << "AxisCount";
    EXPECT_EQ(read_int(board_object(2)) & 0x01, 0x01) << "Options: optionTC";
}

// Every named object of the shared map (objif/names.h) answers on this transport as the map
// declares it: a readable one reads with its declared type, a write-only one says WriteOnly.
// The tool and correction tables (1024 rows each) are sampled: their first, a middle and their
// last row. And a write by name reads back by name.
TEST_P(Conformance, EveryNamedObjectAnswersAsTheMapDeclaresIt) {
    std::size_t checked = 0;
    for (const auto& named : objif::named_objects()) {
        const objif::ObjectInfo& info = *named.info;
        const std::int32_t i = named.address.index;
        if (info.index_last - info.index_first > 16 && i != info.index_first && i != 512 &&
            i != info.index_last)
            continue;
        apci_object_descriptor o{named.address.bus, named.address.device, i,
                                 named.address.subindex, 0};
        const apci_status st = info.type == objif::ValueType::kDouble ? read_double_status(o)
                                                                      : read_int_status(o);
        EXPECT_EQ(st, objif::can_read(info.access) ? APCI_OK : APCI_WRITE_ONLY) << named.name;
        ++checked;
    }
    EXPECT_GT(checked, 200u);  // 224 today: every object but the sampled tables
    const auto* radius = objif::find_object("tc.group[1].radius");
    ASSERT_NE(radius, nullptr);
    const objif::Address a = radius->address;
    ASSERT_EQ(write_double(object(a.bus, a.device, a.index, a.subindex), 3.25), APCI_OK);
    EXPECT_EQ(read_double(object(a.bus, a.device, a.index, a.subindex)), 3.25);
}

TEST_P(Conformance, WrittenIntReadsBack) {
    ASSERT_EQ(write_int(board_object(4), 2000), APCI_OK) << apci_last_error(board_);
    EXPECT_EQ(read_int(board_object(4)), 2000);
}

TEST_P(Conformance, WrittenDoubleReadsBackBitForBit) {
    const double angle = 0.1 + 0.2;  // not representable exactly in decimal
    ASSERT_EQ(write_double(tc_init(APCI_TC_ROT_ANGLE), angle), APCI_OK);
    const double back = read_double(tc_init(APCI_TC_ROT_ANGLE));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(angle));
}

TEST_P(Conformance, FirstAccessFillsTheHandleAndLaterAccessesKeepIt) {
    auto o = tc_group(1, APCI_TC_RADIUS);
    double v = 0;
    ASSERT_EQ(apci_read_double(board_, &o, &v), APCI_OK);
    const std::uint32_t handle = o.handle;
    EXPECT_NE(handle, 0u);
    ASSERT_EQ(apci_write_double(board_, &o, 3.0), APCI_OK);
    EXPECT_EQ(o.handle, handle);
}

TEST_P(Conformance, AddressingErrorsInCheckOrder) {
    EXPECT_EQ(read_int_status(object(999, 0, 1, 0)), APCI_NO_SUCH_DEVICE);
    EXPECT_EQ(read_int_status(object(APCI_TC_BUS, 7, 1, 0)), APCI_NO_SUCH_DEVICE);
    EXPECT_EQ(read_int_status(board_object(99)), APCI_OBJECT_MISSING);
    EXPECT_EQ(read_int_status(tc_group(4, APCI_TC_ERROR)), APCI_OBJECT_MISSING);
    EXPECT_EQ(read_int_status(tc_group(1, 99)), APCI_SUB_MISSING);
}

TEST_P(Conformance, AccessErrors) {
    EXPECT_EQ(write_int(board_object(1), 5), APCI_READ_ONLY) << "FirmwareVersion";
    EXPECT_EQ(read_int_status(tc_init(APCI_TC_CLEAN)), APCI_WRITE_ONLY);
}

TEST_P(Conformance, TypeErrors) {
    EXPECT_EQ(read_int_status(tc_init(APCI_TC_ROT_ANGLE)), APCI_TYPE_MISMATCH);
    EXPECT_EQ(read_double_status(tc_init(APCI_TC_PLANE)), APCI_TYPE_MISMATCH);
    EXPECT_EQ(write_double(tc_init(APCI_TC_PLANE), 17.0), APCI_TYPE_MISMATCH);
}

TEST_P(Conformance, RangeErrors) {
    EXPECT_EQ(write_int(tc_init(APCI_TC_PLANE), 20), APCI_VALUE_TOO_HIGH);
    EXPECT_EQ(write_int(tc_init(APCI_TC_PLANE), 16), APCI_VALUE_TOO_LOW);
    EXPECT_EQ(write_int(tc_group(1, APCI_TC_WKZINDEX), 1024), APCI_VALUE_TOO_HIGH);
}

TEST_P(Conformance, NanAndInfinityAreInvalidValues) {
    EXPECT_EQ(write_double(tc_init(APCI_TC_ROT_ANGLE), std::numeric_limits<double>::quiet_NaN()),
              APCI_INVALID_VALUE);
    EXPECT_EQ(write_double(tc_init(APCI_TC_ROT_ANGLE), std::numeric_limits<double>::infinity()),
              APCI_INVALID_VALUE);
    EXPECT_EQ(read_double(tc_init(APCI_TC_ROT_ANGLE)), 0.0) << "nothing was written";
}

TEST_P(Conformance, RefusedWriteChangesNothing) {
    ASSERT_EQ(write_int(tc_init(APCI_TC_PLANE), 18), APCI_OK);
    EXPECT_EQ(write_int(tc_init(APCI_TC_PLANE), 99), APCI_VALUE_TOO_HIGH);
    EXPECT_EQ(write_double(tc_init(APCI_TC_PLANE), 19.0), APCI_TYPE_MISMATCH);
    EXPECT_EQ(read_int(tc_init(APCI_TC_PLANE)), 18);
}

TEST_P(Conformance, HandleOfAnotherObjectIsAMismatch) {
    auto o = tc_group(1, APCI_TC_RADIUS);
    double v = 0;
    ASSERT_EQ(apci_read_double(board_, &o, &v), APCI_OK);
    o.subindex = APCI_TC_WKZLEN;  // handle kept: names RADIUS
    EXPECT_EQ(apci_read_double(board_, &o, &v), APCI_HANDLE_MISMATCH);
}

TEST_P(Conformance, CleanMakesTcHandlesStaleUntilZeroed) {
    auto radius = tc_group(1, APCI_TC_RADIUS);
    auto clean = tc_init(APCI_TC_CLEAN);
    auto axis_count = board_object(3);
    double r = 0;
    std::int32_t n = 0;
    ASSERT_EQ(apci_write_double(board_, &radius, 4.0), APCI_OK);
    ASSERT_EQ(apci_read_int(board_, &axis_count, &n), APCI_OK);
    ASSERT_EQ(apci_write_int(board_, &clean, 1), APCI_OK);
    EXPECT_EQ(apci_read_double(board_, &radius, &r), APCI_STALE_HANDLE);
    EXPECT_EQ(apci_read_int(board_, &axis_count, &n), APCI_OK) << "bus 1000 handles stay";
    radius.handle = 0;
    ASSERT_EQ(apci_read_double(board_, &radius, &r), APCI_OK);
    EXPECT_EQ(r, 0.0) << "Clean discarded the tool data";
}

TEST_P(Conformance, LastErrorNamesTheOperationObjectAndStatus) {
    EXPECT_EQ(read_int_status(tc_group(1, 99)), APCI_SUB_MISSING);
    const std::string text = apci_last_error(board_);
    EXPECT_NE(text.find("read int 1300/1/1/99"), std::string::npos) << text;
    EXPECT_NE(text.find("SubMissing"), std::string::npos) << text;
    EXPECT_EQ(read_int(board_object(3)), 8);
    EXPECT_STREQ(apci_last_error(board_), "") << "a successful call clears it";
}

TEST_P(Conformance, LinkIsConnectedAndTimeoutIsSettable) {
    EXPECT_EQ(apci_is_connected(board_), 1);
    ASSERT_EQ(apci_set_timeout(board_, 750), APCI_OK);
    std::uint32_t ms = 0;
    ASSERT_EQ(apci_get_timeout(board_, &ms), APCI_OK);
    EXPECT_EQ(ms, 750u);
    EXPECT_EQ(apci_set_timeout(board_, 0), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_reconnect(board_), APCI_OK) << apci_last_error(board_);
    EXPECT_EQ(read_int(board_object(3)), 8) << "the board answers after a reconnect";
}

// ---- TC state rules ([APCI-TC]; docs/design.md section 3)

TEST_P(Conformance, StatusOneWithoutInitialisationIsInitError) {
    EXPECT_EQ(write_int(tc_group(1, APCI_TC_STATUS), 1), APCI_WRONG_DEVICE_STATE);
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_ERROR)), static_cast<std::int32_t>(APCI_TC_ERROR_INIT));
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_STATUS)), 0);
}

TEST_P(Conformance, StatusOneWhenInitialisedSetsRun) {
    initialise_group(1);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_STATUS), 1), APCI_OK) << apci_last_error(board_);
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_STATUS)), static_cast<std::int32_t>(APCI_TC_STATUS_RUN));
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_ERROR)), 0);
}

TEST_P(Conformance, AxisWriteWhileActiveIsRefusedWithInitError) {
    initialise_group(1);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_STATUS), 1), APCI_OK);
    EXPECT_EQ(write_int(tc_group(1, APCI_TC_XAXIS), 3), APCI_WRONG_DEVICE_STATE);
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_XAXIS)), 0) << "refused: unchanged";
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_ERROR)), static_cast<std::int32_t>(APCI_TC_ERROR_INIT));
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_STATUS)), static_cast<std::int32_t>(APCI_TC_STATUS_RUN));
}

TEST_P(Conformance, WritingErrorClearsIt) {
    ASSERT_EQ(write_int(tc_group(2, APCI_TC_STATUS), 1), APCI_WRONG_DEVICE_STATE);
    ASSERT_NE(read_int(tc_group(2, APCI_TC_ERROR)), 0);
    ASSERT_EQ(write_int(tc_group(2, APCI_TC_ERROR), 0), APCI_OK);
    EXPECT_EQ(read_int(tc_group(2, APCI_TC_ERROR)), 0);
}

TEST_P(Conformance, StatusZeroDeactivates) {
    initialise_group(1);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_STATUS), 1), APCI_OK);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_STATUS), 0), APCI_OK);
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_STATUS)), 0);
    EXPECT_EQ(write_int(tc_group(1, APCI_TC_XAXIS), 3), APCI_OK) << "writable again while inactive";
}

TEST_P(Conformance, RadiusBelongsToTheCurrentToolIndex) {
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_WKZINDEX), 5), APCI_OK);
    ASSERT_EQ(write_double(tc_group(1, APCI_TC_RADIUS), 1.5), APCI_OK);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_WKZINDEX), 6), APCI_OK);
    EXPECT_EQ(read_double(tc_group(1, APCI_TC_RADIUS)), 0.0);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_WKZINDEX), 5), APCI_OK);
    EXPECT_EQ(read_double(tc_group(1, APCI_TC_RADIUS)), 1.5);
}

TEST_P(Conformance, IndexZeroFollowsTcPlane) {
    ASSERT_EQ(write_int(tc_group(3, APCI_TC_XAXIS), 2), APCI_OK);
    ASSERT_EQ(write_int(tc_group(3, APCI_TC_YAXIS), 0), APCI_OK);
    ASSERT_EQ(write_int(tc_group(3, APCI_TC_ZAXIS), 1), APCI_OK);
    ASSERT_EQ(write_int(tc_group(3, APCI_TC_WKZINDEX), 33), APCI_OK);
    EXPECT_EQ(read_int(tc_group(0, APCI_TC_WKZINDEX)), 0) << "X-Y plane: group 1";
    ASSERT_EQ(write_int(tc_init(APCI_TC_PLANE), 18), APCI_OK);
    EXPECT_EQ(read_int(tc_group(0, APCI_TC_WKZINDEX)), 33) << "Z-X plane: group 3";
}

TEST_P(Conformance, GroupResetEndsCompensation) {
    initialise_group(1);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_STATUS), 1), APCI_OK);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_GROUP_RESET), 1), APCI_OK);
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_STATUS)), 0);
}

TEST_P(Conformance, WithoutOptionTcEveryTcAccessIsNoSuchDevice) {
    open_board(false);
    EXPECT_EQ(read_int_status(tc_init(APCI_TC_PLANE)), APCI_NO_SUCH_DEVICE);
    EXPECT_EQ(write_double(tc_group(1, APCI_TC_RADIUS), 1.0), APCI_NO_SUCH_DEVICE);
    EXPECT_EQ(read_int(board_object(2)) & 0x01, 0) << "Options: no optionTC";
    EXPECT_EQ(read_int(board_object(3)), 8) << "the board module still answers";
}

// ---- Motion: the same moves, the same positions, cycle for cycle

apci_profile line_to(double x, double y, std::uint32_t tag, double feed = 600.0) {
    apci_profile p{};
    p.kind = APCI_PROFILE_LINE;
    p.axes = 0x03;
    p.tag = tag;
    p.feed = feed;
    p.target[0] = x;
    p.target[1] = y;
    return p;
}

// What a board did for one motion scenario, compared field by field.
struct MotionRecord {
    std::vector<apci_status> statuses;
    std::vector<std::uint64_t> cycles;
    std::vector<double> values;  // positions, trace samples, segment end points
    bool operator==(const MotionRecord&) const = default;
};

MotionRecord run_lines_with_trace(apci_board* b) {
    MotionRecord r;
    r.statuses.push_back(apci_trace_enable(b, 4096));
    r.statuses.push_back(apci_spool_profile(b, ptr(line_to(10.0, 5.0, 1)), nullptr));
    r.statuses.push_back(apci_spool_profile(b, ptr(line_to(-3.25, 7.5, 2)), nullptr));
    apci_motion_status st{};
    r.statuses.push_back(apci_run_until_idle(b, 100000, &st));
    r.cycles.push_back(st.now);
    r.cycles.push_back(st.ran);
    r.values.insert(r.values.end(), st.position, st.position + APCI_AXIS_COUNT);
    std::vector<apci_trace_sample> samples(4096);
    std::size_t n = 0;
    r.statuses.push_back(apci_read_trace(b, samples.data(), samples.size(), &n));
    for (std::size_t i = 0; i < n; ++i) {
        r.cycles.push_back(samples[i].cycle);
        r.values.insert(r.values.end(), samples[i].position, samples[i].position + 2);
    }
    std::vector<apci_segment> segments(16);
    r.statuses.push_back(apci_read_segments(b, segments.data(), segments.size(), &n));
    for (std::size_t i = 0; i < n; ++i) {
        r.cycles.push_back(segments[i].tag);
        r.cycles.push_back(segments[i].end_cycle);
        r.values.insert(r.values.end(), segments[i].end, segments[i].end + 2);
    }
    return r;
}

TEST_P(Conformance, SpooledLinesRunAsOnTheEmbeddedBoardCycleForCycle) {
    apci_board* reference = nullptr;
    ASSERT_EQ(apci_open("emu:", &reference), APCI_OK);
    const MotionRecord expected = run_lines_with_trace(reference);
    apci_close(reference);
    ASSERT_GT(expected.cycles.size(), 100u) << "the lines take many cycles";
    const MotionRecord got = run_lines_with_trace(board_);
    EXPECT_EQ(got.statuses, expected.statuses) << apci_last_error(board_);
    EXPECT_EQ(got.cycles, expected.cycles);
    EXPECT_EQ(got.values, expected.values) << "positions bit for bit";
    EXPECT_EQ(got.values[0], -3.25);
    EXPECT_EQ(got.values[1], 7.5);
}

TEST_P(Conformance, CompensationHoldsAProfileUntilSsf2001) {
    initialise_group(1);
    ASSERT_EQ(write_int(tc_group(1, APCI_TC_STATUS), 1), APCI_OK);
    apci_motion_result result{};
    ASSERT_EQ(apci_spool_profile(board_, ptr(line_to(10.0, 0.0, 1)), &result), APCI_OK)
        << apci_last_error(board_);
    ASSERT_EQ(apci_spool_profile(board_, ptr(line_to(10.0, 10.0, 2)), &result), APCI_OK)
        << apci_last_error(board_);
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_STATUS)),
              static_cast<std::int32_t>(APCI_TC_STATUS_RUN | APCI_TC_STATUS_PROF_MARKED));
    ASSERT_EQ(apci_ssf_command(board_, 0x03, APCI_SSF_RELEASE_HELD_PROFILE, &result), APCI_OK)
        << apci_last_error(board_);
    EXPECT_EQ(read_int(tc_group(1, APCI_TC_STATUS)) &
                  static_cast<std::int32_t>(APCI_TC_STATUS_PROF_MARKED),
              0);
    apci_motion_status st{};
    ASSERT_EQ(apci_run_until_idle(board_, 1000000, &st), APCI_OK);
    EXPECT_NE(st.position[0], 0.0) << "the released profiles ran";
}

// A compensated contour with a tool length: its segments, read through this transport, are the
// embedded board's byte for byte, the length the board added at each end included.
std::vector<apci_segment> run_contour_with_length(apci_board* b) {
    auto write_int = [b](apci_object_descriptor o, std::int32_t v) {
        EXPECT_EQ(apci_write_int(b, &o, v), APCI_OK) << apci_last_error(b);
    };
    auto write_double = [b](apci_object_descriptor o, double v) {
        EXPECT_EQ(apci_write_double(b, &o, v), APCI_OK) << apci_last_error(b);
    };
    write_int(tc_group(1, APCI_TC_XAXIS), 0);
    write_int(tc_group(1, APCI_TC_YAXIS), 1);
    write_int(tc_group(1, APCI_TC_ZAXIS), 2);
    write_double(tc_group(1, APCI_TC_RADIUS), 2.0);
    write_double(tc_group(1, APCI_TC_WKZLEN), 7.5);
    write_int(tc_group(1, APCI_TC_RIGHT), 1);
    write_int(tc_group(1, APCI_TC_STATUS), 1);
    EXPECT_EQ(apci_spool_profile(b, ptr(line_to(10.0, 0.0, 1)), nullptr), APCI_OK);
    EXPECT_EQ(apci_spool_profile(b, ptr(line_to(10.0, 10.0, 2)), nullptr), APCI_OK);
    write_int(tc_group(1, APCI_TC_STATUS), 0);
    EXPECT_EQ(apci_run_until_idle(b, 1000000, nullptr), APCI_OK);
    std::vector<apci_segment> segments(16);
    std::size_t n = 0;
    EXPECT_EQ(apci_read_segments(b, segments.data(), segments.size(), &n), APCI_OK);
    segments.resize(n);
    return segments;
}

// Every member of a segment, the doubles as their bits.
std::vector<std::uint64_t> record_of(const apci_segment& s) {
    std::vector<std::uint64_t> r = {s.tag,           s.kind,          s.role,
                                    s.ccw,           s.interrupted,   s.traverse,
                                    s.plane_axes[0], s.plane_axes[1], std::bit_cast<std::uint32_t>(s.plane),
                                    s.start_cycle,   s.end_cycle,     std::bit_cast<std::uint64_t>(s.feed)};
    for (const double* axes : {s.start, s.end, s.center, s.length_start, s.length_end})
        for (int a = 0; a < APCI_AXIS_COUNT; ++a) r.push_back(std::bit_cast<std::uint64_t>(axes[a]));
    return r;
}

TEST_P(Conformance, SegmentsCarryTheToolLengthAsOnTheEmbeddedBoard) {
    apci_board* reference = nullptr;
    ASSERT_EQ(apci_open("emu:", &reference), APCI_OK);
    const std::vector<apci_segment> expected = run_contour_with_length(reference);
    apci_close(reference);
    const std::vector<apci_segment> got = run_contour_with_length(board_);
    ASSERT_EQ(got.size(), expected.size());
    ASSERT_GE(got.size(), 3u);
    EXPECT_EQ(got.front().length_start[2], 0.0) << "the approach brings the length in";
    EXPECT_EQ(got.front().length_end[2], 7.5);
    EXPECT_EQ(got.back().length_start[2], 7.5) << "the departure takes it out";
    EXPECT_EQ(got.back().length_end[2], 0.0);
    for (std::size_t i = 0; i < got.size(); ++i)
        EXPECT_EQ(record_of(got[i]), record_of(expected[i])) << "segment " << i;
}

TEST_P(Conformance, DirectCommandDiscardsTheSpooler) {
    ASSERT_EQ(apci_spool_profile(board_, ptr(line_to(50.0, 0.0, 1)), nullptr), APCI_OK);
    ASSERT_EQ(apci_spool_profile(board_, ptr(line_to(50.0, 50.0, 2)), nullptr), APCI_OK);
    apci_direct_command stop{};
    stop.code = APCI_DIRECT_JS;
    ASSERT_EQ(apci_direct_command_send(board_, &stop), APCI_OK) << apci_last_error(board_);
    std::uint32_t fill = 99, capacity = 0;
    ASSERT_EQ(apci_spooler_fill(board_, &fill, &capacity), APCI_OK);
    EXPECT_EQ(fill, 0u);
    EXPECT_GT(capacity, 0u);
}

TEST_P(Conformance, RefusedProfileChangesNothing) {
    apci_profile bad = line_to(1.0, 1.0, 1);
    bad.feed = -5.0;
    apci_board* reference = nullptr;
    ASSERT_EQ(apci_open("emu:", &reference), APCI_OK);
    const apci_status expected = apci_spool_profile(reference, &bad, nullptr);
    apci_close(reference);
    ASSERT_NE(expected, APCI_OK);
    EXPECT_EQ(apci_spool_profile(board_, &bad, nullptr), expected);
    std::uint32_t fill = 99, capacity = 0;
    ASSERT_EQ(apci_spooler_fill(board_, &fill, &capacity), APCI_OK);
    EXPECT_EQ(fill, 0u);
}

std::string transport_name(const ::testing::TestParamInfo<Transport>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Transports, Conformance, ::testing::ValuesIn(conformance::transports()),
                         transport_name);

}  // namespace
