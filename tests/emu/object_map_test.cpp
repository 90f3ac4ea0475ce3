// SPDX-License-Identifier: MIT
// Every object of the object map (docs/object-map.md), buses 1000, 1300, 1310 and 1330:
// read gives the default, a valid write reads back, the wrong type is
// refused, values out of range are refused, and the wrong access kind is
// refused; every refusal leaves the state unchanged. The expected rows are
// written here from the spec page, not taken from the module tables, and
// EveryDeclaredObjectIsCovered keeps the two in step.
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "emu_test_util.h"
#include "objif/names.h"

using namespace emu_test;
using objif::Access;
using objif::Address;
namespace board = rwmos::board;
namespace tc = rwmos::tc;
namespace otc = rwmos::otc;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct BadValue {
    Value value;
    Status expect;
};

struct ObjectRow {
    std::string name;  // test name suffix
    Address address;
    ValueType type;
    Access access;
    Value default_value;            // for readable objects
    std::optional<Value> valid;     // a value the write accepts (writable objects)
    bool reads_back = true;         // a readable object returns `valid` after the write
    std::vector<BadValue> out_of_range;
};

Value I(std::int32_t v) { return Value::of_int(v); }
Value D(double v) { return Value::of_double(v); }
BadValue low(Value v) { return {v, Status::kValueTooLow}; }
BadValue high(Value v) { return {v, Status::kValueTooHigh}; }
BadValue invalid(double v) { return {D(v), Status::kInvalidValue}; }

Address B(std::int32_t idx, std::int32_t sub = 0) { return {board::kBus, board::kDevice, idx, sub}; }
Address T0(std::int32_t idx, std::int32_t sub = 0) { return {tc::kBus, tc::kDevInit, idx, sub}; }
Address T1(std::int32_t sub) { return {tc::kBus, tc::kDevGroups, 1, sub}; }
namespace c3 = rwmos::comp3d;
Address C0(std::int32_t idx, std::int32_t sub = 0) { return {c3::kBus, c3::kDevSettings, idx, sub}; }
Address C1(std::int32_t sub) { return {c3::kBus, c3::kDevTools, 1, sub}; }
Address C2(std::int32_t sub) { return {c3::kBus, c3::kDevCorrections, 1, sub}; }
namespace tcomp = rwmos::tempcomp;
Address TT(std::int32_t idx, std::int32_t sub = 0) { return {tcomp::kBus, tcomp::kDevice, idx, sub}; }
// The range of a 3D compensation value (+-1e5) with NaN and infinity.
std::vector<BadValue> c3_range(double min = -1.0e5) {
    return {low(D(min - (min == 0.0 ? 0.001 : 1.0))), high(D(1.0e5 + 1.0)), invalid(kNaN), invalid(kInf)};
}
Address O0(std::int32_t idx, std::int32_t sub = 0) { return {otc::kBus, otc::kDevChannel, idx, sub}; }
Address O1(std::int32_t sub) { return {otc::kBus, otc::kDevAxisUnits, 1, sub}; }
Address O2(std::int32_t idx, std::int32_t sub = 0) { return {otc::kBus, otc::kDevTool, idx, sub}; }

std::vector<ObjectRow> object_rows() {
    const auto kI = ValueType::kInt32;
    const auto kD = ValueType::kDouble;
    const auto r = Access::kRead;
    const auto w = Access::kWrite;
    const auto rw = Access::kReadWrite;
    std::vector<ObjectRow> rows{
        // ---- Board, bus 1000.
        {"FirmwareVersion", B(1), kI, r, I(0x010000), {}, true, {}},
        {"Options", B(2), kI, r, I(board::kOptionTc | board::kOptionOtc | board::kOptionTempComp), {}, true, {}},
        {"AxisCount", B(3), kI, r, I(8), {}, true, {}},
        {"InterpolationCycle", B(4), kI, rw, I(1000), I(2000), true, {low(I(249)), high(I(10001))}},
        {"PU", B(5), kI, rw, I(0), I(2), true, {low(I(-1)), high(I(3))}},
        {"SpoolerCapacity", B(6), kI, r, I(256), {}, true, {}},
        {"SpoolerFill", B(7), kI, r, I(0), {}, true, {}},
        {"rs", B(30), kI, w, I(0), I(0), false, {}},
        // ---- TC DeviceNumber 0.
        {"Clean", T0(1), kI, w, I(1), I(1), false, {low(I(0)), high(I(2))}},
        {"X_Axis_Nr", T0(11, 0), kI, rw, I(0), I(5), true, {low(I(-1)), high(I(8))}},
        {"Y_Axis_Nr", T0(11, 1), kI, rw, I(1), I(6), true, {low(I(-1)), high(I(8))}},
        {"Z_Axis_Nr", T0(11, 2), kI, rw, I(2), I(7), true, {low(I(-1)), high(I(8))}},
        {"TcPlane", T0(12), kI, rw, I(17), I(19), true, {low(I(16)), high(I(20))}},
        {"ReInit", T0(13), kI, w, I(0), I(12345), false, {}},
        {"Reset", T0(14), kI, w, I(0), I(-7), false, {}},
        {"RotAngle", T0(20), kD, rw, D(0.0), D(-45.5), true, {invalid(kNaN), invalid(kInf), invalid(-kInf)}},
        {"RotCenterX", T0(21), kD, rw, D(0.0), D(12.25), true, {invalid(kNaN), invalid(kInf)}},
        {"RotCenterY", T0(22), kD, rw, D(0.0), D(-3.5), true, {invalid(kNaN), invalid(-kInf)}},
        // ---- TC DeviceNumber 1, group 1.
        {"ERROR", T1(1), kI, rw, I(0), I(0x1F), false, {}},
        {"RESET", T1(2), kI, w, I(0), I(99), false, {}},
        {"STATUS", T1(3), kI, rw, I(0), I(0), true, {low(I(-1)), high(I(2))}},
        {"XAxis", T1(4), kI, rw, I(0), I(3), true, {low(I(-1)), high(I(8))}},
        {"YAxis", T1(5), kI, rw, I(1), I(4), true, {low(I(-1)), high(I(8))}},
        {"RADIUS", T1(7), kD, rw, D(0.0), D(2.5), true,
         {low(D(-0.001)), high(D(1.0e6 + 1.0)), invalid(kNaN), invalid(kInf)}},
        {"WKZINDEX", T1(8), kI, rw, I(0), I(1023), true, {low(I(-1)), high(I(1024))}},
        {"Left", T1(9), kI, w, I(0), I(-1), false, {}},
        {"Right", T1(10), kI, w, I(0), I(2'000'000'000), false, {}},
        {"ZAxis", T1(11), kI, rw, I(2), I(7), true, {low(I(-1)), high(I(8))}},
        {"WkzLen", T1(12), kD, rw, D(0.0), D(-12.5), true,
         {low(D(-1.0e6 - 1.0)), high(D(1.0e6 + 1.0)), invalid(kNaN), invalid(-kInf)}},
        {"CornerMode", T1(20), kI, rw, I(26), I(25), true, {low(I(24)), high(I(27))}},
        {"Side", T1(21), kI, r, I(40), {}, true, {}},
        // Every value but 138, 139, 237 is InvalidValue (docs/object-map.md), below and above too.
        {"SelectionMode", T1(22), kI, rw, I(237), I(139), true,
         {{I(137), Status::kInvalidValue}, {I(238), Status::kInvalidValue},
          {I(140), Status::kInvalidValue}, {I(236), Status::kInvalidValue},
          {I(std::numeric_limits<std::int32_t>::min()), Status::kInvalidValue},
          {I(std::numeric_limits<std::int32_t>::max()), Status::kInvalidValue}}},
        {"LengthMode", T1(23), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"CuttingEdge", T1(24), kI, rw, I(0), I(9), true, {low(I(-1)), high(I(10))}},
        // ---- 3D compensation, bus 1310, DeviceNumber 0.
        {"C3_Tool", C0(1), kI, rw, I(0), I(1023), true, {low(I(-1)), high(I(1024))}},
        {"C3_CallDL", C0(2, 0), kD, rw, D(0.0), D(-0.5), true, c3_range()},
        {"C3_CallDR", C0(2, 1), kD, rw, D(0.0), D(-0.25), true, c3_range()},
        {"C3_CallDR2", C0(2, 2), kD, rw, D(0.0), D(0.125), true, c3_range()},
        {"C3_CorrectionRow", C0(3), kI, rw, I(0), I(1023), true, {low(I(-1)), high(I(1024))}},
        {"C3_ProgPath", C0(4), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"C3_Reference", C0(5), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"C3_Tcpm", C0(6), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"C3_AllowOversize", C0(7), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"C3_Side", C0(8), kI, rw, I(40), I(41), true, {low(I(39)), high(I(43))}},
        {"C3_HeadAxisB", C0(9), kI, rw, I(4), I(7), true, {low(I(-1)), high(I(8))}},
        {"C3_HeadAxisC", C0(10), kI, rw, I(-1), I(5), true, {low(I(-2)), high(I(8))}},
        {"C3_NX", C0(11, 0), kD, rw, D(0.0), D(0.6), true, c3_range()},
        {"C3_NY", C0(11, 1), kD, rw, D(0.0), D(-0.8), true, c3_range()},
        {"C3_NZ", C0(11, 2), kD, rw, D(0.0), D(1.0), true, c3_range()},
        {"C3_TX", C0(12, 0), kD, rw, D(0.0), D(0.6), true, c3_range()},
        {"C3_TY", C0(12, 1), kD, rw, D(0.0), D(-0.8), true, c3_range()},
        {"C3_TZ", C0(12, 2), kD, rw, D(0.0), D(1.0), true, c3_range()},
        {"C3_Arm", C0(13), kI, rw, I(0), I(4), true, {low(I(-1)), high(I(8))}},
        {"C3_LastError", C0(14), kI, rw, I(0), I(5), false, {}},
        {"C3_DL", C0(20, 0), kD, r, D(0.0), {}, true, {}},
        {"C3_DR", C0(20, 1), kD, r, D(0.0), {}, true, {}},
        {"C3_DR2", C0(20, 2), kD, r, D(0.0), {}, true, {}},
        {"C3_LastTipX", C0(21, 0), kD, r, D(0.0), {}, true, {}},
        {"C3_LastTipY", C0(21, 1), kD, r, D(0.0), {}, true, {}},
        {"C3_LastTipZ", C0(21, 2), kD, r, D(0.0), {}, true, {}},
        // ---- 3D compensation, DeviceNumber 1 (tool table) and 2 (correction table), row 1.
        {"C3_ToolR", C1(1), kD, rw, D(0.0), D(3.0), true, c3_range(0.0)},
        {"C3_ToolR2", C1(2), kD, rw, D(0.0), D(3.0), true, c3_range(0.0)},
        {"C3_ToolDL", C1(3), kD, rw, D(0.0), D(-0.1), true, c3_range()},
        {"C3_ToolDR", C1(4), kD, rw, D(0.0), D(-0.1), true, c3_range()},
        {"C3_ToolDR2", C1(5), kD, rw, D(0.0), D(-0.1), true, c3_range()},
        {"C3_CorrDL", C2(1), kD, rw, D(0.0), D(0.01), true, c3_range()},
        {"C3_CorrDR", C2(2), kD, rw, D(0.0), D(-0.02), true, c3_range()},
        {"C3_CorrDR2", C2(3), kD, rw, D(0.0), D(0.03), true, c3_range()},
        // ---- OTC DeviceNumber 0.
        {"OtcActive", O0(1), kI, rw, I(0), I(0), true, {low(I(-1)), high(I(2))}},
        {"OtcProcessingType", O0(2), kI, rw, I(1), I(3), true, {low(I(-1)), high(I(4))}},
        {"OtcMode", O0(3), kI, rw, I(2), I(1), true, {low(I(-1)), high(I(3))}},
        {"OtcWearConst", O0(4), kD, rw, D(0.0), D(500.0), true, {low(D(-0.5)), invalid(kNaN), invalid(kInf)}},
        {"OtcWearConstSource", O0(5), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"OtcAccWeight", O0(6), kI, rw, I(100), I(1), true, {low(I(0)), high(I(101))}},
        {"OtcLastError", O0(7), kI, rw, I(0), I(5), false, {}},
        {"OtcEffectiveWearConst", O0(8), kD, r, D(0.0), {}, true, {}},
        {"OtcRampVelocity", O0(10), kD, rw, D(0.5), D(2.0), true, {low(D(0.0)), high(D(1.0e6 + 1.0)), invalid(kNaN)}},
        {"OtcRampAcceleration", O0(11), kD, rw, D(1.0), D(0.25), true, {low(D(-1.0)), high(D(2.0e6)), invalid(kInf)}},
        {"OtcKinematics", O0(12), kI, rw, I(0), I(4), true, {low(I(-1)), high(I(5)), {I(2), Status::kInvalidValue}}},
        {"OtcTrafo", O0(13), kI, rw, I(0), I(0), true, {low(I(-1)), high(I(2))}},
        {"OtcToolAxisB", O0(14), kI, rw, I(4), I(5), true, {low(I(-1)), high(I(8))}},
        {"OtcRadiusOffsetCommand", O0(20, 1), kI, rw, I(0), I(0), true, {}},
        {"OtcRadiusOffsetEnable", O0(20, 2), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"OtcRadiusOffsetRequest", O0(20, 3), kI, r, I(0), {}, true, {}},
        {"OtcRadiusOffsetState", O0(20, 4), kI, r, I(0), {}, true, {}},
        // ---- OTC DeviceNumber 1, axis 1.
        {"OtcOffsetCommand", O1(1), kI, rw, I(0), I(0), true, {}},
        {"OtcOffsetEnable", O1(2), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"OtcOffsetRequest", O1(3), kI, r, I(0), {}, true, {}},
        {"OtcOffsetState", O1(4), kI, r, I(0), {}, true, {}},
        {"BackToStartCommand", O1(5), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"BackToStartEnable", O1(6), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"BackToStartRequest", O1(7), kI, r, I(0), {}, true, {}},
        {"BackToStartState", O1(8), kI, r, I(0), {}, true, {}},
        // ---- OTC DeviceNumber 2.
        {"OtcToolNumber", O2(1), kI, rw, I(0), I(1023), true, {low(I(-1)), high(I(1024))}},
        {"OtcToolType", O2(2), kI, rw, I(0), I(2), true, {low(I(-1)), high(I(4))}},
        {"OtcToolWearConst", O2(3), kD, rw, D(0.0), D(100000.0), true, {low(D(-1.0)), invalid(kNaN)}},
        {"OtcToolMaxInfeed", O2(4), kD, rw, D(0.0), D(200000.0), true,
         {low(D(-2147483649.0)), high(D(2147483648.0)), invalid(kNaN)}},
        {"OtcToolTiltAngle", O2(5), kD, rw, D(0.0), D(-450000.0), true,
         {low(D(-450001.0)), high(D(450001.0)), invalid(kInf)}},
        {"OtcWearRadius", O2(10), kD, r, D(0.0), {}, true, {}},
        {"OtcWearRadiusCont", O2(11), kD, r, D(0.0), {}, true, {}},
        // ---- Temperature compensation, bus 1320.
        {"TT_TOOL_TEMP_COMP0", TT(1, 0), kD, rw, D(0.0), D(0.01), true, c3_range()},
        {"TT_TOOL_TEMP_COMP1", TT(1, 1), kD, rw, D(0.0), D(-0.02), true, c3_range()},
        {"TT_TOOL_TEMP_COMP2", TT(1, 2), kD, rw, D(0.0), D(0.03), true, c3_range()},
        {"TT_TOOL_TEMP_COMP_ON", TT(2), kI, rw, I(0), I(-7), true, {}},  // int32: not 0 is on
        {"TT_ToolHolder", TT(4), kI, rw, I(0), I(1), true, {low(I(-1)), high(I(2))}},
        {"TT_HeadAxisB", TT(5), kI, rw, I(4), I(6), true, {low(I(-1)), high(I(8))}},
        {"TT_HeadAxisC", TT(6), kI, rw, I(-1), I(5), true, {low(I(-2)), high(I(8))}},
        {"TT_RampVelocity", TT(7), kD, rw, D(1.0), D(2.5), true,
         {low(D(0.0)), high(D(1.0e5 + 1.0)), invalid(kNaN), invalid(kInf)}},
    };
    for (std::int32_t axis = 0; axis < 8; ++axis) {
        rows.push_back({"TT_TEMP_COMP_TYPE" + std::to_string(axis), TT(3, axis), kI, rw, I(0),
                        I(4), true, {low(I(-1)), high(I(256))}});
        rows.push_back(
            {"TT_Offset" + std::to_string(axis), TT(10, axis), kD, r, D(0.0), {}, true, {}});
    }
    for (std::int32_t axis = 0; axis < 8; ++axis)
        rows.push_back({"OtcWear" + std::to_string(axis), O2(12, axis), kD, r, D(0.0), {}, true, {}});
    for (std::int32_t axis = 0; axis < 8; ++axis)
        rows.push_back({"Position" + std::to_string(axis), B(10, axis), kD, r, D(0.0), {}, true, {}});
    return rows;
}

Descriptor descriptor(const ObjectRow& row) { return Descriptor{row.address, objif::kNoHandle}; }
ValueType other(ValueType t) { return t == ValueType::kInt32 ? ValueType::kDouble : ValueType::kInt32; }
Value of_other_type(const ObjectRow& row) {
    return row.type == ValueType::kInt32 ? Value::of_double(1.0) : Value::of_int(1);
}

template <class Pred>
std::vector<ObjectRow> rows_where(Pred pred) {
    std::vector<ObjectRow> out;
    for (auto& row : object_rows())
        if (pred(row)) out.push_back(row);
    return out;
}
bool readable(const ObjectRow& r) { return objif::can_read(r.access); }
bool writable(const ObjectRow& r) { return objif::can_write(r.access); }

class ObjectRead : public BoardFixture, public ::testing::WithParamInterface<ObjectRow> {};
class ObjectWrite : public BoardFixture, public ::testing::WithParamInterface<ObjectRow> {};
class ObjectType : public BoardFixture, public ::testing::WithParamInterface<ObjectRow> {};
class ObjectRange : public BoardFixture, public ::testing::WithParamInterface<ObjectRow> {};
class ObjectAccess : public BoardFixture, public ::testing::WithParamInterface<ObjectRow> {};

TEST_P(ObjectRead, ReadGivesTheDefault) {
    const ObjectRow& row = GetParam();
    auto d = descriptor(row);
    Value v;
    ASSERT_EQ(board.read(d, row.type, v), Status::kOk);
    EXPECT_EQ(v, row.default_value);
    EXPECT_NE(d.handle, objif::kNoHandle) << "a resolved descriptor carries its handle";
}

TEST_P(ObjectWrite, ValidWriteIsAcceptedAndReadsBack) {
    const ObjectRow& row = GetParam();
    ASSERT_TRUE(row.valid.has_value());
    auto d = descriptor(row);
    ASSERT_EQ(board.write(d, *row.valid), Status::kOk);
    if (!readable(row) || !row.reads_back) return;
    auto again = descriptor(row);
    Value v;
    ASSERT_EQ(board.read(again, row.type, v), Status::kOk);
    EXPECT_EQ(v, *row.valid);
}

TEST_P(ObjectType, WrongTypeIsTypeMismatchAndChangesNothing) {
    const ObjectRow& row = GetParam();
    const auto before = snapshot(board);
    if (readable(row)) {
        auto d = descriptor(row);
        Value v;
        EXPECT_EQ(board.read(d, other(row.type), v), Status::kTypeMismatch);
    }
    if (writable(row)) {
        auto d = descriptor(row);
        EXPECT_EQ(board.write(d, of_other_type(row)), Status::kTypeMismatch);
    }
    EXPECT_TRUE(unchanged(before, board));
}

TEST_P(ObjectRange, OutOfRangeIsRefusedAndChangesNothing) {
    const ObjectRow& row = GetParam();
    const auto before = snapshot(board);
    for (const auto& bad : row.out_of_range) {
        auto d = descriptor(row);
        EXPECT_EQ(board.write(d, bad.value), bad.expect) << "value " << bad.value.to_string();
    }
    EXPECT_TRUE(unchanged(before, board));
}

TEST_P(ObjectAccess, WrongAccessIsRefusedAndChangesNothing) {
    const ObjectRow& row = GetParam();
    const auto before = snapshot(board);
    auto d = descriptor(row);
    Value v;
    if (row.access == Access::kRead) {
        // Access is checked before type and range: even a wrong-typed NaN is ReadOnly.
        EXPECT_EQ(board.write(d, Value::of_double(kNaN)), Status::kReadOnly);
        EXPECT_EQ(board.write(d, row.default_value), Status::kReadOnly);
    } else {
        EXPECT_EQ(board.read(d, row.type, v), Status::kWriteOnly);
        EXPECT_EQ(board.read(d, other(row.type), v), Status::kWriteOnly);
    }
    EXPECT_TRUE(unchanged(before, board));
}

std::string row_name(const ::testing::TestParamInfo<ObjectRow>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(EveryReadableObject, ObjectRead, ::testing::ValuesIn(rows_where(readable)), row_name);
INSTANTIATE_TEST_SUITE_P(EveryWritableObject, ObjectWrite, ::testing::ValuesIn(rows_where(writable)), row_name);
INSTANTIATE_TEST_SUITE_P(EveryObject, ObjectType, ::testing::ValuesIn(object_rows()), row_name);
INSTANTIATE_TEST_SUITE_P(EveryRangedObject, ObjectRange,
                         ::testing::ValuesIn(rows_where([](const ObjectRow& r) { return !r.out_of_range.empty(); })),
                         row_name);
INSTANTIATE_TEST_SUITE_P(EveryOneWayObject, ObjectAccess,
                         ::testing::ValuesIn(rows_where([](const ObjectRow& r) { return r.access != Access::kReadWrite; })),
                         row_name);

// Objects whose range is the whole int32 type cannot be written out of range;
// the rows without out-of-range values are exactly those (and read-only ones).
TEST(ObjectMapCoverage, RowsWithoutRangeValuesAreFullRangeOrReadOnly) {
    rwmos::EmulatedBoard board;
    for (const auto& row : object_rows()) {
        if (!row.out_of_range.empty() || !writable(row)) continue;
        objif::Status why;
        const auto* info = board.dictionary().module(row.address.bus)->find(row.address, why);
        ASSERT_NE(info, nullptr) << row.name;
        EXPECT_EQ(info->min, objif::kInt32Min) << row.name;
        EXPECT_EQ(info->max, objif::kInt32Max) << row.name;
    }
}

// The rows above name every object both modules declare, with its type and access.
TEST(ObjectMapCoverage, EveryDeclaredObjectIsCovered) {
    rwmos::EmulatedBoard board;
    const auto rows = object_rows();
    std::size_t declared = 0;
    for (auto* module : board.dictionary().modules()) {
        for (std::size_t i = 0; i < module->object_count(); ++i) {
            const auto& info = module->object_at(i);
            ++declared;
            const Address probe{module->bus(), info.device, info.index_first == 0 ? 1 : info.index_first,
                                info.subindex};
            bool found = false;
            for (const auto& row : rows) {
                if (!(row.address == probe)) continue;
                found = true;
                EXPECT_EQ(row.type, info.type) << info.name;
                EXPECT_EQ(row.access, info.access) << info.name;
                if (objif::can_read(info.access)) {
                    EXPECT_EQ(row.default_value, info.default_value) << info.name;
                }
            }
            EXPECT_TRUE(found) << "no test row for " << info.name << " at " << probe.to_string();
        }
    }
    EXPECT_EQ(declared, rows.size());
}

}  // namespace

namespace {

// The board serves the shared map (objif/map/objects.h) row for row: what a host names by the
// map is what the emulator answers.
TEST(ObjectMapCoverage, TheBoardServesExactlyTheSharedMap) {
    rwmos::EmulatedBoard board;
    std::size_t modules_seen = 0;
    for (auto* module : board.dictionary().modules()) {
        const objif::map::ModuleMap* map = nullptr;
        for (const auto& m : objif::map::kModules)
            if (m.bus == module->bus()) map = &m;
        ASSERT_NE(map, nullptr) << "bus " << module->bus() << " is not in the shared map";
        ++modules_seen;
        ASSERT_EQ(module->object_count(), map->objects.size()) << map->key;
        for (std::size_t i = 0; i < map->objects.size(); ++i) {
            const auto& served = module->object_at(i);
            const auto& declared = map->objects[i];
            EXPECT_EQ(served.name, declared.name);
            EXPECT_EQ(served.device, declared.device) << declared.name;
            EXPECT_EQ(served.index_first, declared.index_first) << declared.name;
            EXPECT_EQ(served.index_last, declared.index_last) << declared.name;
            EXPECT_EQ(served.subindex, declared.subindex) << declared.name;
            EXPECT_EQ(served.type, declared.type) << declared.name;
            EXPECT_EQ(served.access, declared.access) << declared.name;
            EXPECT_EQ(served.min, declared.min) << declared.name;
            EXPECT_EQ(served.max, declared.max) << declared.name;
            EXPECT_EQ(served.key, declared.key) << declared.name;
            EXPECT_EQ(served.unit, declared.unit) << declared.name;
        }
    }
    EXPECT_EQ(modules_seen, objif::map::kModules.size());
}

// Every name of the map reaches an object on a fresh board: a readable one reads with its
// declared type, a write-only one answers kWriteOnly to a read (never an address error).
TEST(ObjectMapCoverage, EveryNameReachesItsObjectOnAFreshBoard) {
    rwmos::EmulatedBoard board;
    for (const auto& named : objif::named_objects()) {
        objif::Descriptor d{named.address, objif::kNoHandle};
        Value out;
        const Status st = board.read(d, named.info->type, out);
        if (objif::can_read(named.info->access)) {
            EXPECT_EQ(st, Status::kOk) << named.name;
            EXPECT_EQ(out.type(), named.info->type) << named.name;
        } else {
            EXPECT_EQ(st, Status::kWriteOnly) << named.name;
        }
    }
}

}  // namespace
