// SPDX-License-Identifier: MIT
// The board's object map, part 2: every object the board serves, declared once as a table per
// module (bus): where it lives, its name, type, access, range, default, unit and the rule it
// follows. The host reads it to name objects (objif/names.h, `apcictl dump`, the Python
// package); the emulator attaches its hooks to the same rows (objif::attach in
// objif/dictionary.h), so what the host knows and what the board serves cannot drift apart.
// docs/object-map.md is the spec page, its name list generated from these tables.
//
// Dotted names (objif/names.h): MODULE[.DEVICE][[INDEX]].KEY, e.g. tc.group[1].radius; a
// device covering a range of indices takes the index in brackets, a module of one device has
// no device part (board.axis_count).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

#include "objif/map/cutting_edge.h"
#include "objif/map/object_map.h"
#include "objif/object_info.h"

namespace objif::map {

// One device (DeviceNumber) of a module and its part of the dotted name ("" for a module of
// one device).
struct DeviceMap {
    std::int32_t device = 0;
    std::string_view key;
};

// One module (BusNumber): the first part of the dotted names, its devices and its objects.
struct ModuleMap {
    std::int32_t bus = 0;
    std::string_view key;    // "tc"
    std::string_view title;  // "tool compensation (TC)"
    std::span<const DeviceMap> devices;
    std::span<const ObjectInfo> objects;
};

namespace detail {
inline constexpr double kIntMin = kInt32Min;
inline constexpr double kIntMax = kInt32Max;
inline constexpr double kDoubleMin = std::numeric_limits<double>::lowest();
inline constexpr double kDoubleMax = std::numeric_limits<double>::max();
inline constexpr auto kInt = ValueType::kInt32;
inline constexpr auto kDouble = ValueType::kDouble;
inline constexpr auto kR = Access::kRead;
inline constexpr auto kW = Access::kWrite;
inline constexpr auto kRW = Access::kReadWrite;

// A row with its dotted-name key and unit.
constexpr ObjectInfo named(std::string_view key, std::string_view unit, ObjectInfo info) {
    info.key = key;
    info.unit = unit;
    return info;
}
}  // namespace detail

// ---- Board module, bus 1000 (design: docs/design.md section 4 "Board").
namespace board {
namespace detail {
using namespace objif::map::detail;
inline constexpr std::string_view kDesign = "design: docs/design.md section 4 Board";
constexpr ObjectInfo ro_int(std::int32_t index, std::string_view name, std::int32_t def) {
    return {kDevice,
            index,
            index,
            0,
            name,
            ValueType::kInt32,
            Access::kRead,
            kIntMin,
            kIntMax,
            Value::of_int(def),
            kDesign,
            {},
            {}};
}
inline constexpr std::array<std::string_view, kAxisCount> kPositionNames{
    "Position0", "Position1", "Position2", "Position3",
    "Position4", "Position5", "Position6", "Position7"};
inline constexpr std::array<std::string_view, kAxisCount> kPositionKeys{
    "position[0]", "position[1]", "position[2]", "position[3]",
    "position[4]", "position[5]", "position[6]", "position[7]"};
constexpr ObjectInfo position(std::int32_t axis) {
    const auto i = static_cast<std::size_t>(axis);
    return named(kPositionKeys[i], "mm",
                 {kDevice,
                  kIdxAxisPosition,
                  kIdxAxisPosition,
                  axis,
                  kPositionNames[i],
                  ValueType::kDouble,
                  Access::kRead,
                  kDoubleMin,
                  kDoubleMax,
                  Value::of_double(0.0),
                  "design: axis position, written by the motion layer",
                  {},
                  {}});
}
}  // namespace detail

inline constexpr std::array<ObjectInfo, 16> kObjects = [] {
    using namespace detail;
    return std::array<ObjectInfo, 16>{{
        named("firmware_version", "",
              ro_int(board::kIdxFirmwareVersion, "FirmwareVersion", kFirmwareVersion)),
        named("options", "",
              ro_int(board::kIdxOptions, "Options",
                     board::kOptionTc | board::kOptionOtc | board::kOptionTempComp)),
        named("axis_count", "", ro_int(board::kIdxAxisCount, "AxisCount", kAxisCount)),
        named("interpolation_cycle", "us",
              ObjectInfo{board::kDevice,
                         board::kIdxInterpolationCycle,
                         board::kIdxInterpolationCycle,
                         0,
                         "InterpolationCycle",
                         ValueType::kInt32,
                         Access::kReadWrite,
                         kMinInterpolationCycleUs,
                         kMaxInterpolationCycleUs,
                         Value::of_int(kDefaultInterpolationCycleUs),
                         "design: docs/design.md section 4, default 1 ms, in microseconds",
                         {},
                         {}}),
        named("pu", "",
              ObjectInfo{
                  board::kDevice,
                  board::kIdxPu,
                  board::kIdxPu,
                  0,
                  "PU",
                  ValueType::kInt32,
                  Access::kReadWrite,
                  board::kPuMillimetre,
                  board::kPuInch,
                  Value::of_int(board::kPuMillimetre),
                  "design: unit of RADIUS/WkzLen ([APCI-TC] Table 3 'mit PU angewaehlte Einheit')",
                  {},
                  {}}),
        named("spooler_capacity", "profiles",
              ro_int(board::kIdxSpoolerCapacity, "SpoolerCapacity", kSpoolerCapacity)),
        named("spooler_fill", "profiles", ro_int(board::kIdxSpoolerFill, "SpoolerFill", 0)),
        position(0),
        position(1),
        position(2),
        position(3),
        position(4),
        position(5),
        position(6),
        position(7),
        named("rs", "",
              ObjectInfo{board::kDevice,
                         board::kIdxRs,
                         board::kIdxRs,
                         0,
                         "rs",
                         ValueType::kInt32,
                         Access::kWrite,
                         kIntMin,
                         kIntMax,
                         Value::of_int(0),
                         "[APCI-TC] Table 2: rs() zeroes RotAngle, RotCenterX, RotCenterY",
                         {},
                         {}}),
    }};
}();
inline constexpr std::array<DeviceMap, 1> kDevices{{{kDevice, ""}}};
}  // namespace board

// ---- TC module, bus 1300 ([APCI-TC] Tables 2 and 3).
namespace tc {
namespace detail {
using namespace objif::map::detail;
inline constexpr double kLastAxis = board::kAxisCount - 1;
constexpr ObjectInfo init_object(std::int32_t index, std::int32_t sub, std::string_view name,
                                 ValueType type, Access access, double min, double max, Value def,
                                 std::string_view rule) {
    return {kDevInit, index, index, sub, name, type, access, min, max, def, rule, {}, {}};
}
constexpr ObjectInfo group_object(std::int32_t sub, std::string_view name, ValueType type,
                                  Access access, double min, double max, Value def,
                                  std::string_view rule) {
    return {kDevGroups,  kActiveGroupIndex,
            kGroupCount, sub,
            name,        type,
            access,      min,
            max,         def,
            rule,        {},
            {}};
}
}  // namespace detail

inline constexpr std::array<ObjectInfo, 26> kObjects = [] {
    using namespace detail;
    return std::array<ObjectInfo, 26>{{
        // ---- DeviceNumber 0: initialisation ([APCI-TC] Table 2).
        named("clean", "",
              init_object(
                  tc::kIdxClean, 0, "Clean", kInt, kW, 1, 1, Value::of_int(1),
                  "[APCI-TC] Table 2 Clean: parameter 1; drops all TC objects, handles stale")),
        named("x_axis_nr", "",
              init_object(tc::kIdxAxisNr, tc::kSubX, "X-Axis-Nr", kInt, kRW, 0, kLastAxis,
                          Value::of_int(0), "[APCI-TC] Table 2: board axis used as X")),
        named("y_axis_nr", "",
              init_object(tc::kIdxAxisNr, tc::kSubY, "Y-Axis-Nr", kInt, kRW, 0, kLastAxis,
                          Value::of_int(1), "[APCI-TC] Table 2: board axis used as Y")),
        named("z_axis_nr", "",
              init_object(tc::kIdxAxisNr, tc::kSubZ, "Z-Axis-Nr", kInt, kRW, 0, kLastAxis,
                          Value::of_int(2), "[APCI-TC] Table 2: board axis used as Z")),
        named(
            "tc_plane", "",
            init_object(tc::kIdxTcPlane, 0, "TcPlane", kInt, kRW, tc::kPlaneXY, tc::kPlaneYZ,
                        Value::of_int(tc::kPlaneXY), "[APCI-TC] Table 2: 17 X-Y, 18 Z-X, 19 Y-Z")),
        named("reinit", "",
              init_object(
                  tc::kIdxReInit, 0, "ReInit", kInt, kW, kIntMin, kIntMax, Value::of_int(0),
                  "[APCI-TC] Table 2 ReInit (index: design): clear stored offsets; tools stay; "
                  "refused while a profile is held (not emulated)")),
        named("reset", "",
              init_object(
                  tc::kIdxReset, 0, "Reset", kInt, kW, kIntMin, kIntMax, Value::of_int(0),
                  "[APCI-TC] Table 2 Reset (index: design): stop corrections, clear offsets and "
                  "held profiles; tools stay")),
        named("rot_angle", "deg",
              init_object(tc::kIdxRotAngle, 0, "RotAngle", kDouble, kRW, kDoubleMin, kDoubleMax,
                          Value::of_double(0.0),
                          "[APCI-TC] Table 2 / 2.1.1: degrees; zeroed by rs()")),
        named("rot_center_x", "mm",
              init_object(tc::kIdxRotCenterX, 0, "RotCenterX", kDouble, kRW, kDoubleMin, kDoubleMax,
                          Value::of_double(0.0),
                          "[APCI-TC] Table 2: first plane axis; zeroed by rs()")),
        named("rot_center_y", "mm",
              init_object(tc::kIdxRotCenterY, 0, "RotCenterY", kDouble, kRW, kDoubleMin, kDoubleMax,
                          Value::of_double(0.0),
                          "[APCI-TC] Table 2: second plane axis; zeroed by rs()")),
        // ---- DeviceNumber 1: compensation groups ([APCI-TC] Table 3), Index 0..3.
        named("error", "",
              group_object(tc::kSubError, "ERROR", kInt, kRW, kIntMin, kIntMax, Value::of_int(0),
                           "[APCI-TC] Table 3/4: error bits; a write clears them")),
        named("reset", "",
              group_object(tc::kSubReset, "RESET", kInt, kW, kIntMin, kIntMax, Value::of_int(0),
                           "[APCI-TC] Table 3: ends compensation, discards programmed values; "
                           "Index and value meaningless")),
        named("status", "",
              group_object(
                  tc::kSubStatus, "STATUS", kInt, kRW, 0, 1, Value::of_int(0),
                  "[APCI-TC] Table 3/5: 1 activates (InitError if uninitialised), 0 deactivates")),
        named("x_axis", "",
              group_object(tc::kSubXAxis, "XAxis", kInt, kRW, 0, kLastAxis, Value::of_int(0),
                           "[APCI-TC] Table 3: only while inactive, else InitError")),
        named("y_axis", "",
              group_object(tc::kSubYAxis, "YAxis", kInt, kRW, 0, kLastAxis, Value::of_int(1),
                           "[APCI-TC] Table 3: only while inactive, else InitError")),
        named("radius", "PU",
              group_object(tc::kSubRadius, "RADIUS", kDouble, kRW, 0.0, kMaxRadius,
                           Value::of_double(0.0),
                           "[APCI-TC] Table 3: radius of the current WKZINDEX's tool, PU units")),
        named("wkz_index", "",
              group_object(tc::kSubWkzIndex, "WKZINDEX", kInt, kRW, 0, tc::kToolCount - 1,
                           Value::of_int(0),
                           "[APCI-TC] Table 3: tool index 0..1023, only while inactive")),
        named("left", "",
              group_object(
                  tc::kSubLeft, "Left", kInt, kW, kIntMin, kIntMax, Value::of_int(0),
                  "[APCI-TC] Table 3: select left (G41); only while inactive; value unused")),
        named("right", "",
              group_object(
                  tc::kSubRight, "Right", kInt, kW, kIntMin, kIntMax, Value::of_int(0),
                  "[APCI-TC] Table 3: select right (G42); only while inactive; value unused")),
        named("z_axis", "",
              group_object(tc::kSubZAxis, "ZAxis", kInt, kRW, 0, kLastAxis, Value::of_int(2),
                           "[APCI-TC] Table 3: only while inactive, else InitError")),
        named("wkz_len", "PU",
              group_object(tc::kSubWkzLen, "WkzLen", kDouble, kRW, -kMaxLength, kMaxLength,
                           Value::of_double(0.0),
                           "[APCI-TC] Table 3: length of the current WKZINDEX's tool, PU units")),
        named("corner_mode", "",
              group_object(
                  tc::kSubCornerMode, "CornerMode", kInt, kRW, tc::kCornerLinear,
                  tc::kCornerCircular, Value::of_int(tc::kCornerCircular),
                  "design: corners 26 circular (default) / 25 linear (docs/design.md section 3)")),
        named("side", "",
              group_object(
                  tc::kSubSide, "Side", kInt, kR, tc::kSideNone, tc::kSideRight,
                  Value::of_int(tc::kSideNone),
                  "design: reads back the Left/Right selection: 40 none, 41 left, 42 right")),
        named("selection_mode", "",
              group_object(
                  tc::kSubSelectionMode, "SelectionMode", kInt, kRW,
                  std::numeric_limits<std::int32_t>::min(),
                  std::numeric_limits<std::int32_t>::max(),
                  Value::of_int(tc::kSelectionPerpendicular),
                  "design: approach and departure, 237 perpendicular (default) / 139 indirect / "
                  "138 direct; any other value InvalidValue (docs/compensation.md)")),
        named("length_mode", "",
              group_object(
                  tc::kSubLengthMode, "LengthMode", kInt, kRW, tc::kLengthWhileCompensating,
                  tc::kLengthAlways, Value::of_int(tc::kLengthWhileCompensating),
                  "design: WkzLen on ZAxis 0 while compensating (default) / 1 on every profile "
                  "(docs/compensation.md)")),
        named("cutting_edge", "",
              group_object(
                  tc::kSubCuttingEdge, "CuttingEdge", kInt, kRW, tc::kCuttingEdgeNone,
                  tc::kMaxCuttingEdge, Value::of_int(tc::kCuttingEdgeNone),
                  "design: the cutting edge position 1..9 of the tool WKZINDEX selects (ISG "
                  "P-TOOL-00002, LinuxCNC's Q); 0 and 9 the nose centre (docs/compensation.md)")),
    }};
}();
inline constexpr std::array<DeviceMap, 2> kDevices{{{kDevInit, "init"}, {kDevGroups, "group"}}};
}  // namespace tc

// ---- 3D tool compensation module, bus 1310 ([TNC-3D]; docs/3d-compensation.md).
namespace comp3d {
namespace detail {
using namespace objif::map::detail;
inline constexpr double kMax = kMaxValue;
inline constexpr double kLastAxis = board::kAxisCount - 1;
inline constexpr double kLastTool = kToolCount - 1;
inline constexpr double kLastRow = kCorrectionRows - 1;
inline constexpr std::string_view kCall =
    "[TNC-3D]: delta of the TOOL CALL; taken by the next Tool write";
inline constexpr std::string_view kVectorN =
    "[TNC-3D] LN: surface normal of the next LN profile (armed with Arm)";
inline constexpr std::string_view kVectorT =
    "[TNC-3D] LN: tool vector of the next LN profile (armed with Arm)";
inline constexpr std::string_view kSum = "[TNC-3D]: tool table + TOOL CALL + correction table";
inline constexpr std::string_view kTip = "design: the last compensated tool tip (TCP)";
constexpr ObjectInfo setting(std::int32_t index, std::int32_t sub, std::string_view name,
                             ValueType type, Access access, double min, double max, Value def,
                             std::string_view rule) {
    return {kDevSettings, index, index, sub, name, type, access, min, max, def, rule, {}, {}};
}
constexpr ObjectInfo tool_row(std::int32_t sub, std::string_view name, double min,
                              std::string_view rule) {
    return {kDevTools, 0,    kToolCount - 1,        sub,  name, kDouble, Access::kReadWrite,
            min,       kMax, Value::of_double(0.0), rule, {},   {}};
}
constexpr ObjectInfo correction_row(std::int32_t sub, std::string_view name) {
    return {kDevCorrections,
            0,
            kCorrectionRows - 1,
            sub,
            name,
            kDouble,
            Access::kReadWrite,
            -kMax,
            kMax,
            Value::of_double(0.0),
            "[TNC-3D]: delta from the correction table, summed with tool table and TOOL CALL",
            {},
            {}};
}
}  // namespace detail

inline constexpr std::array<ObjectInfo, 34> kObjects = [] {
    using namespace detail;
    return std::array<ObjectInfo, 34>{{
        // ---- DeviceNumber 0.
        named("tool", "",
              setting(comp3d::kIdxTool, 0, "Tool", kInt, kRW, 0, kLastTool, Value::of_int(0),
                      "[TNC-3D] TOOL CALL: loads the tool with CallDeltas; refused with a positive "
                      "oversize unless AllowOversize (M107)")),
        named("call_dl", "mm",
              setting(comp3d::kIdxCallDeltas, 0, "CallDL", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kCall)),
        named("call_dr", "mm",
              setting(comp3d::kIdxCallDeltas, 1, "CallDR", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kCall)),
        named("call_dr2", "mm",
              setting(comp3d::kIdxCallDeltas, 2, "CallDR2", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kCall)),
        named("correction_row", "",
              setting(comp3d::kIdxCorrectionRow, 0, "CorrectionRow", kInt, kRW, 0, kLastRow,
                      Value::of_int(0), "[TNC-3D]: the correction table row in force")),
        named(
            "prog_path", "",
            setting(comp3d::kIdxProgPath, 0, "ProgPath", kInt, kRW, 0, 1, Value::of_int(0),
                    "[TNC-3D] FUNCTION PROG PATH: 0 OFF (deltas only), 1 IS CONTOUR (full radii)")),
        named("reference", "",
              setting(comp3d::kIdxReference, 0, "Reference", kInt, kRW, 0, 1, Value::of_int(0),
                      "[TNC-3D] TCPM REFPNT: 0 tip, 1 centre")),
        named("tcpm", "",
              setting(comp3d::kIdxTcpm, 0, "Tcpm", kInt, kRW, 0, 1, Value::of_int(0),
                      "[TNC-3D] M128 / FUNCTION TCPM: 1 the LN's T (or N) orients the tool")),
        named("allow_oversize", "",
              setting(
                  comp3d::kIdxAllowOversize, 0, "AllowOversize", kInt, kRW, 0, 1, Value::of_int(0),
                  "[TNC-3D] M107 (1) / M108 (0): 0 refused while the loaded tool is oversized")),
        named("side", "",
              setting(comp3d::kIdxSide, 0, "Side", kInt, kRW, tc::kSideNone, tc::kSideRight,
                      Value::of_int(tc::kSideNone),
                      "[TNC-3D] peripheral milling: 40 R0, 41 RL, 42 RR (LN without N)")),
        named("head_axis_b", "",
              setting(comp3d::kIdxHeadAxisB, 0, "HeadAxisB", kInt, kRW, 0, kLastAxis,
                      Value::of_int(4),
                      "design: board axis of the head's B (degrees), kinematics.h")),
        named("head_axis_c", "",
              setting(comp3d::kIdxHeadAxisC, 0, "HeadAxisC", kInt, kRW, comp3d::kNoHeadAxis,
                      kLastAxis, Value::of_int(comp3d::kNoHeadAxis),
                      "design: board axis of the head's C (degrees), -1 none")),
        named("nx", "",
              setting(comp3d::kIdxSurfaceNormal, 0, "NX", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kVectorN)),
        named("ny", "",
              setting(comp3d::kIdxSurfaceNormal, 1, "NY", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kVectorN)),
        named("nz", "",
              setting(comp3d::kIdxSurfaceNormal, 2, "NZ", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kVectorN)),
        named("tx", "",
              setting(comp3d::kIdxToolVector, 0, "TX", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kVectorT)),
        named("ty", "",
              setting(comp3d::kIdxToolVector, 1, "TY", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kVectorT)),
        named("tz", "",
              setting(comp3d::kIdxToolVector, 2, "TZ", kDouble, kRW, -kMax, kMax,
                      Value::of_double(0.0), kVectorT)),
        named("arm", "",
              setting(comp3d::kIdxArm, 0, "Arm", kInt, kRW, 0, 7, Value::of_int(0),
                      "[TNC-3D] LN: bit 0 N, bit 1 T, bit 2 a line without vectors (L with RL/RR) "
                      "for the next profile; refused when a vector is not normalised")),
        named("last_error", "",
              setting(comp3d::kIdxLastError, 0, "LastError", kInt, kRW, kIntMin, kIntMax,
                      Value::of_int(0),
                      "design: the Refusal code of the last refusal; a write clears")),
        named("dl", "mm",
              setting(comp3d::kIdxDeltas, 0, "DL", kDouble, kR, -kMax, kMax, Value::of_double(0.0),
                      kSum)),
        named("dr", "mm",
              setting(comp3d::kIdxDeltas, 1, "DR", kDouble, kR, -kMax, kMax, Value::of_double(0.0),
                      kSum)),
        named("dr2", "mm",
              setting(comp3d::kIdxDeltas, 2, "DR2", kDouble, kR, -kMax, kMax, Value::of_double(0.0),
                      kSum)),
        named("last_tip_x", "mm",
              setting(comp3d::kIdxLastTip, 0, "LastTipX", kDouble, kR, -kMax, kMax,
                      Value::of_double(0.0), kTip)),
        named("last_tip_y", "mm",
              setting(comp3d::kIdxLastTip, 1, "LastTipY", kDouble, kR, -kMax, kMax,
                      Value::of_double(0.0), kTip)),
        named("last_tip_z", "mm",
              setting(comp3d::kIdxLastTip, 2, "LastTipZ", kDouble, kR, -kMax, kMax,
                      Value::of_double(0.0), kTip)),
        // ---- DeviceNumber 1: tool table ([TNC-3D] "Werkzeugtabelle tool.t": R, R2, DL, DR, DR2).
        named("r", "mm", tool_row(comp3d::kSubR, "R", 0.0, "[TNC-3D]: tool radius R")),
        named(
            "r2", "mm",
            tool_row(comp3d::kSubR2, "R2", 0.0, "[TNC-3D]: corner radius R2 (0 end mill, R ball)")),
        named("dl", "mm",
              tool_row(comp3d::kSubDl, "DL", -kMax, "[TNC-3D]: delta of the tool table on L")),
        named("dr", "mm",
              tool_row(comp3d::kSubDr, "DR", -kMax, "[TNC-3D]: delta of the tool table on R")),
        named("dr2", "mm",
              tool_row(comp3d::kSubDr2, "DR2", -kMax, "[TNC-3D]: delta of the tool table on R2")),
        // ---- DeviceNumber 2: correction table.
        named("dl", "mm", correction_row(comp3d::kSubCorrDl, "CorrDL")),
        named("dr", "mm", correction_row(comp3d::kSubCorrDr, "CorrDR")),
        named("dr2", "mm", correction_row(comp3d::kSubCorrDr2, "CorrDR2")),
    }};
}();
inline constexpr std::array<DeviceMap, 3> kDevices{
    {{kDevSettings, "settings"}, {kDevTools, "tool"}, {kDevCorrections, "correction"}}};
}  // namespace comp3d

// ---- Temperature compensation in tool direction, bus 1320 ([SIN-TEMP]).
namespace tempcomp {
namespace detail {
using namespace objif::map::detail;
inline constexpr double kMax = kMaxValue;
inline constexpr double kLastAxis = board::kAxisCount - 1;
inline constexpr std::string_view kSd =
    "[SIN-TEMP]: SD 42960 TOOL_TEMP_COMP, a component of the vector on the geometry axes; "
    "acts at once";
inline constexpr std::string_view kMd32750 =
    "[SIN-TEMP]: MD 32750 TEMP_COMP_TYPE of the axis; bit 2 (4): the axis takes the vector";
inline constexpr std::string_view kOffset =
    "design: the displacement the axis got at the last interpolation cycle";
inline constexpr std::array<std::string_view, board::kAxisCount> kTypeNames{
    "TEMP_COMP_TYPE[0]", "TEMP_COMP_TYPE[1]", "TEMP_COMP_TYPE[2]", "TEMP_COMP_TYPE[3]",
    "TEMP_COMP_TYPE[4]", "TEMP_COMP_TYPE[5]", "TEMP_COMP_TYPE[6]", "TEMP_COMP_TYPE[7]"};
inline constexpr std::array<std::string_view, board::kAxisCount> kTypeKeys{
    "temp_comp_type[0]", "temp_comp_type[1]", "temp_comp_type[2]", "temp_comp_type[3]",
    "temp_comp_type[4]", "temp_comp_type[5]", "temp_comp_type[6]", "temp_comp_type[7]"};
inline constexpr std::array<std::string_view, board::kAxisCount> kOffsetNames{
    "Offset0", "Offset1", "Offset2", "Offset3", "Offset4", "Offset5", "Offset6", "Offset7"};
inline constexpr std::array<std::string_view, board::kAxisCount> kOffsetKeys{
    "offset[0]", "offset[1]", "offset[2]", "offset[3]",
    "offset[4]", "offset[5]", "offset[6]", "offset[7]"};
constexpr ObjectInfo obj(std::int32_t index, std::int32_t sub, std::string_view name,
                         ValueType type, Access access, double min, double max, Value def,
                         std::string_view rule) {
    return {kDevice, index, index, sub, name, type, access, min, max, def, rule, {}, {}};
}
constexpr ObjectInfo type(std::int32_t axis) {
    const auto i = static_cast<std::size_t>(axis);
    return named(
        kTypeKeys[i], "",
        obj(kIdxTempCompType, axis, kTypeNames[i], kInt, kRW, 0, 255, Value::of_int(0), kMd32750));
}
constexpr ObjectInfo offset(std::int32_t axis) {
    const auto i = static_cast<std::size_t>(axis);
    return named(kOffsetKeys[i], "mm",
                 obj(kIdxOffset, axis, kOffsetNames[i], kDouble, kR, -kMax, kMax,
                     Value::of_double(0.0), kOffset));
}
}  // namespace detail

inline constexpr std::array<ObjectInfo, 24> kObjects = [] {
    using namespace detail;
    return std::array<ObjectInfo, 24>{{
        named("tool_temp_comp[0]", "mm",
              obj(tempcomp::kIdxToolTempComp, 0, "TOOL_TEMP_COMP[0]", kDouble, kRW, -kMax, kMax,
                  Value::of_double(0.0), kSd)),
        named("tool_temp_comp[1]", "mm",
              obj(tempcomp::kIdxToolTempComp, 1, "TOOL_TEMP_COMP[1]", kDouble, kRW, -kMax, kMax,
                  Value::of_double(0.0), kSd)),
        named("tool_temp_comp[2]", "mm",
              obj(tempcomp::kIdxToolTempComp, 2, "TOOL_TEMP_COMP[2]", kDouble, kRW, -kMax, kMax,
                  Value::of_double(0.0), kSd)),
        named("tool_temp_comp_on", "",
              obj(tempcomp::kIdxToolTempCompOn, 0, "TOOL_TEMP_COMP_ON", kInt, kRW, objif::kInt32Min,
                  objif::kInt32Max, Value::of_int(0),
                  "[SIN-TEMP]: MD 20390, any value but 0 activates the compensation; kept as "
                  "written")),
        type(0),
        type(1),
        type(2),
        type(3),
        type(4),
        type(5),
        type(6),
        type(7),
        named("tool_holder", "",
              obj(tempcomp::kIdxToolHolder, 0, "ToolHolder", kInt, kRW, 0, 1, Value::of_int(0),
                  "[SIN-TEMP]: orientable tool holder active: the vector turns with the head (B, "
                  "C)")),
        named("head_axis_b", "",
              obj(tempcomp::kIdxHeadAxisB, 0, "HeadAxisB", kInt, kRW, 0, kLastAxis,
                  Value::of_int(4), "design: board axis of the head's B (degrees), kinematics.h")),
        named("head_axis_c", "",
              obj(tempcomp::kIdxHeadAxisC, 0, "HeadAxisC", kInt, kRW, tempcomp::kNoHeadAxis,
                  kLastAxis, Value::of_int(tempcomp::kNoHeadAxis),
                  "design: board axis of the head's C, -1 none")),
        named("ramp_velocity", "mm/s",
              obj(tempcomp::kIdxRampVelocity, 0, "RampVelocity", kDouble, kRW,
                  tempcomp::kMinRampVelocity, tempcomp::kMaxRampVelocity,
                  Value::of_double(tempcomp::kDefaultRampVelocity),
                  "design: mm/s at which an axis that left the geometry axes goes to zero")),
        offset(0),
        offset(1),
        offset(2),
        offset(3),
        offset(4),
        offset(5),
        offset(6),
        offset(7),
    }};
}();
inline constexpr std::array<DeviceMap, 1> kDevices{{{kDevice, ""}}};
}  // namespace tempcomp

// ---- OTC module, bus 1330: online tool (wear) compensation ([ISG-OTC]; docs/otc.md).
namespace otc {
namespace detail {
using namespace objif::map::detail;
inline constexpr double kLastAxis = kAxisCount - 1;
inline constexpr double kMaxTiltUnits = kMaxTiltDegrees / kTiltUnitInDegrees;
inline constexpr auto kCh = kDevChannel;
inline constexpr auto kTool = kDevTool;
inline constexpr auto kUnit = kIdxRadiusOffsetUnit;
constexpr ObjectInfo obj(std::int32_t dev, std::int32_t index, std::int32_t sub,
                         std::string_view name, ValueType type, Access access, double min,
                         double max, Value def, std::string_view rule) {
    return {dev, index, index, sub, name, type, access, min, max, def, rule, {}, {}};
}
constexpr ObjectInfo axis_unit_obj(std::int32_t sub, std::string_view name, ValueType type,
                                   Access access, double min, double max, std::string_view rule) {
    return {kDevAxisUnits, 0,   kAxisCount - 1,   sub,  name, type, access,
            min,           max, Value::of_int(0), rule, {},   {}};
}
}  // namespace detail

inline constexpr std::array<ObjectInfo, 40> kObjects = [] {
    using namespace detail;
    return std::array<ObjectInfo, 40>{{
        // ---- DeviceNumber 0: #OTC ([ISG-OTC] section 2.1), ramp, kinematics, channel unit.
        named(
            "active", "",
            obj(kCh, otc::kIdxActive, 0, "Active", kInt, kRW, 0, 1, Value::of_int(0),
                "[ISG-OTC] 2.1/2.8: V.G.OTC_ACTIVE; 1 = #OTC ON (tool type 2, else P-ERR-21391), "
                "0 = #OTC OFF (G40 first in RADIUS; folds the wear); Busy while moves are queued")),
        named("processing_type", "",
              obj(kCh, otc::kIdxProcessingType, 0, "ProcessingType", kInt, kRW, 0, 3,
                  Value::of_int(1),
                  "[ISG-OTC] 2.1: 0 RADIUS, 1 LENGTH (default), 2 TOOL_DIR, 3 SURF_NORM_DIR; not "
                  "while "
                  "on")),
        named("mode", "",
              obj(kCh, otc::kIdxMode, 0, "Mode", kInt, kRW, 0, 2, Value::of_int(2),
                  "[ISG-OTC] 2.1: 0 CONT, 1 DISC, 2 AUTO (default); not while on")),
        named("wear_const", "0.1 um/m",
              obj(kCh, otc::kIdxWearConst, 0, "WearConst", kDouble, kRW, 0.0, kDoubleMax,
                  Value::of_double(0.0),
                  "[ISG-OTC] 2.1 WEAR_CONST=..: 0.1 um/m, modal; a write also selects it "
                  "(WearConstSource 1)")),
        named("wear_const_source", "",
              obj(kCh, otc::kIdxWearConstSource, 0, "WearConstSource", kInt, kRW, 0, 1,
                  Value::of_int(0),
                  "[ISG-OTC] 2.1: 0 WEAR_CONST_TOOL (default), 1 the programmed WEAR_CONST")),
        named("acc_weight", "%",
              obj(kCh, otc::kIdxAccWeight, 0, "AccWeight", kInt, kRW, otc::kMinAccWeight,
                  otc::kMaxAccWeight, Value::of_int(otc::kDefaultAccWeight),
                  "[ISG-OTC] 2.1 ACC_WEIGHT: percent [1;100] of the ramp acceleration; not while "
                  "on")),
        named("last_error", "",
              obj(kCh, otc::kIdxLastError, 0, "LastError", kInt, kRW, kIntMin, kIntMax,
                  Value::of_int(0),
                  "design: number of the last refused rule (21391 = P-ERR-21391); a write clears "
                  "it")),
        named(
            "effective_wear_const", "0.1 um/m",
            obj(kCh, otc::kIdxEffectiveWearConst, 0, "EffectiveWearConst", kDouble, kR, 0.0,
                kDoubleMax, Value::of_double(0.0), "design: the wear constant in force, 0.1 um/m")),
        named("ramp_velocity", "mm/s",
              obj(kCh, otc::kIdxRampVelocity, 0, "RampVelocity", kDouble, kRW, kMinRamp, kMaxRamp,
                  Value::of_double(kDefaultRampVelocity),
                  "design: largest speed of a discrete offset, mm/s ([ISG-OTC]: over several "
                  "cycles)")),
        named("ramp_acceleration", "mm/s^2",
              obj(kCh, otc::kIdxRampAcceleration, 0, "RampAcceleration", kDouble, kRW, kMinRamp,
                  kMaxRamp, Value::of_double(kDefaultRampAcceleration),
                  "design: largest acceleration of a discrete offset at ACC_WEIGHT 100, mm/s^2")),
        named(
            "kinematics", "",
            obj(kCh, otc::kIdxKinematics, 0, "Kinematics", kInt, kRW, 0, kBHeadKinematics,
                Value::of_int(0),
                "design: #KIN ID; 0 none, 4 the B head (docs/design.md section 8); not while on")),
        named("trafo", "",
              obj(kCh, otc::kIdxTrafo, 0, "Trafo", kInt, kRW, 0, 1, Value::of_int(0),
                  "design: #TRAFO ON/OFF; with the B head on, TOOL_DIR/SURF_NORM_DIR follow B; not "
                  "while on")),
        named("tool_axis_b", "",
              obj(kCh, otc::kIdxToolAxisB, 0, "ToolAxisB", kInt, kRW, 0, kLastAxis,
                  Value::of_int(kDefaultToolAxisB),
                  "design: board axis of the B head's B; not while on")),
        named(
            "radius_offset.command", "0.1 um",
            obj(kCh, kUnit, otc::kSubCommand, "otc_radius_offset.command_w", kInt, kRW, kIntMin,
                kIntMax, Value::of_int(0),
                "[ISG-OTC] 2.7.1: 0.1 um within [-P-TOOL-00031, P-TOOL-00031]; RADIUS or TOOL_DIR, "
                "DISC/AUTO")),
        named("radius_offset.enable", "",
              obj(kCh, kUnit, otc::kSubEnable, "otc_radius_offset.enable_w", kInt, kRW, 0, 1,
                  Value::of_int(0), "[ISG-OTC] 2.7.1: the PLC enables the unit")),
        named("radius_offset.request", "0.1 um",
              obj(kCh, kUnit, otc::kSubRequest, "otc_radius_offset.request_r", kInt, kR, kIntMin,
                  kIntMax, Value::of_int(0),
                  "design reading of 2.7.1: the offset the ramp heads for, 0.1 um")),
        named(
            "radius_offset.state", "0.1 um",
            obj(kCh, kUnit, otc::kSubState, "otc_radius_offset.state_r", kInt, kR, kIntMin, kIntMax,
                Value::of_int(0), "design reading of 2.7.1: the offset reached, 0.1 um")),
        // ---- DeviceNumber 1: otc_offset of every board axis ([ISG-OTC] section 2.7.2).
        named("command", "0.1 um",
              axis_unit_obj(
                  otc::kSubCommand, "otc_offset.command_w", kInt, kRW, kIntMin, kIntMax,
                  "[ISG-OTC] 2.7.2: 0.1 um within [-P-TOOL-00031, P-TOOL-00031]; RADIUS, LENGTH; "
                  "third axis along the direction in TOOL_DIR/SURF_NORM_DIR")),
        named("enable", "",
              axis_unit_obj(otc::kSubEnable, "otc_offset.enable_w", kInt, kRW, 0, 1,
                            "[ISG-OTC] 2.7.2: the PLC enables the unit")),
        named("request", "0.1 um",
              axis_unit_obj(otc::kSubRequest, "otc_offset.request_r", kInt, kR, kIntMin, kIntMax,
                            "design reading of 2.7.2: the offset the ramp heads for, 0.1 um")),
        named("state", "0.1 um",
              axis_unit_obj(otc::kSubState, "otc_offset.state_r", kInt, kR, kIntMin, kIntMax,
                            "design reading of 2.7.2: the offset reached, 0.1 um")),
        // ManualMvBackToStart of every board axis ([ISG-OTC] section 2.7.3).
        named("back_to_start.command", "",
              axis_unit_obj(otc::kSubBackCommand, "ManualMvBackToStart.X_Command", kInt, kRW, 0,
                            1,
                            "[ISG-OTC] 2.7.3: a rising edge (0 to 1) with X_Enable moves the axis "
                            "so that its manual offset is 0, in manual mode with the axis at rest "
                            "and an offset; else ignored")),
        named("back_to_start.enable", "",
              axis_unit_obj(otc::kSubBackEnable, "ManualMvBackToStart.X_Enable", kInt, kRW, 0, 1,
                            "[ISG-OTC] 2.7.3: the PLC enables the unit")),
        named("back_to_start.request", "",
              axis_unit_obj(otc::kSubBackRequest, "ManualMvBackToStart.X_Request", kInt, kR, 0, 1,
                            "design reading of 2.7.3: X_Command while the unit is enabled")),
        named("back_to_start.state", "",
              axis_unit_obj(otc::kSubBackState, "ManualMvBackToStart.X_State", kInt, kR, 0, 1,
                            "design reading of 2.7.3: 1 while the axis moves back")),
        // ---- DeviceNumber 2: the current tool (V.G.WZ_AKT; [ISG-OTC] sections 2.6, 2.8, 3.2).
        named(
            "number", "",
            obj(kTool, otc::kIdxToolNumber, 0, "ToolNumber", kInt, kRW, 0, tc::kToolCount - 1,
                Value::of_int(0),
                "design: the tool (D n, TC WKZINDEX) the wear folds into; a change starts its wear "
                "from 0 ([ISG-OTC] section 2.9); not while on")),
        named("type", "",
              obj(kTool, otc::kIdxToolType, 0, "typ", kInt, kRW, 0, 3, Value::of_int(0),
                  "[ISG-OTC] 3.2 P-TOOL-00001: 0 milling, 1 turning, 2 grinding, 3 wire; not while "
                  "on")),
        named("wear_const", "0.1 um/m",
              obj(kTool, otc::kIdxToolWearConst, 0, "grinding_wear_const", kDouble, kRW, 0.0,
                  kDoubleMax, Value::of_double(0.0),
                  "[ISG-OTC] 3.2 P-TOOL-00030, 0.1 um/m; V.G.WZ_AKT.WEAR_CONST (2.8: read and "
                  "write)")),
        named("max_infeed", "0.1 um",
              obj(kTool, otc::kIdxToolMaxInfeed, 0, "grinding_max_infeed", kDouble, kRW, kIntMin,
                  kIntMax, Value::of_double(0.0),
                  "[ISG-OTC] 3.2 P-TOOL-00031: 0.1 um, SGN32 range; 0: no discrete offset; "
                  "not while on")),
        named("tilt_angle", "0.0001 deg",
              obj(kTool, otc::kIdxToolTiltAngle, 0, "grinding_disc_tilt_angle", kDouble, kRW,
                  -kMaxTiltUnits, kMaxTiltUnits, Value::of_double(0.0),
                  "[ISG-OTC] 3.2 P-TOOL-00138: 0.0001 degree within [-45, 45] degrees; not while "
                  "on")),
        named("wear_radius", "mm",
              obj(kTool, otc::kIdxWearRadius, 0, "V.G.WZ_AKT.WEAR_RADIUS", kDouble, kR, -kDoubleMax,
                  kDoubleMax, Value::of_double(0.0),
                  "[ISG-OTC] 2.8: radius wear, discrete + continuous, mm; updated at #OTC OFF")),
        named("wear_radius_cont", "mm",
              obj(kTool, otc::kIdxWearRadiusCont, 0, "V.G.WZ_AKT.WEAR_RADIUS_CONT", kDouble, kR,
                  -kDoubleMax, kDoubleMax, Value::of_double(0.0),
                  "[ISG-OTC] 2.8: continuous radius wear, mm; updated at #OTC OFF")),
        named("wear[0]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         0,
                         "V.G.WZ_AKT.WEAR[0]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 0, mm; updated at #OTC OFF",
                         {},
                         {}}),
        named("wear[1]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         1,
                         "V.G.WZ_AKT.WEAR[1]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 1",
                         {},
                         {}}),
        named("wear[2]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         2,
                         "V.G.WZ_AKT.WEAR[2]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 2",
                         {},
                         {}}),
        named("wear[3]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         3,
                         "V.G.WZ_AKT.WEAR[3]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 3",
                         {},
                         {}}),
        named("wear[4]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         4,
                         "V.G.WZ_AKT.WEAR[4]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 4",
                         {},
                         {}}),
        named("wear[5]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         5,
                         "V.G.WZ_AKT.WEAR[5]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 5",
                         {},
                         {}}),
        named("wear[6]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         6,
                         "V.G.WZ_AKT.WEAR[6]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 6",
                         {},
                         {}}),
        named("wear[7]", "mm",
              ObjectInfo{kTool,
                         otc::kIdxWear,
                         otc::kIdxWear,
                         7,
                         "V.G.WZ_AKT.WEAR[7]",
                         kDouble,
                         kR,
                         -kDoubleMax,
                         kDoubleMax,
                         Value::of_double(0.0),
                         "[ISG-OTC] 2.8: wear on axis 7",
                         {},
                         {}}),
    }};
}();
inline constexpr std::array<DeviceMap, 3> kDevices{
    {{kDevChannel, "channel"}, {kDevAxisUnits, "axis"}, {kDevTool, "tool"}}};
}  // namespace otc

// Every module of the map, in bus order.
inline constexpr std::array<ModuleMap, 5> kModules{{
    {board::kBus, "board", "board", board::kDevices, board::kObjects},
    {tc::kBus, "tc", "tool compensation (TC)", tc::kDevices, tc::kObjects},
    {comp3d::kBus, "comp3d", "3D tool compensation", comp3d::kDevices, comp3d::kObjects},
    {tempcomp::kBus, "tempcomp", "temperature compensation in tool direction", tempcomp::kDevices,
     tempcomp::kObjects},
    {otc::kBus, "otc", "online tool compensation (OTC)", otc::kDevices, otc::kObjects},
}};

}  // namespace objif::map
