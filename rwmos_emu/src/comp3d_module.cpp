// SPDX-License-Identifier: MIT
// 3D tool compensation module, bus 1310 ([TNC-3D]; design numbers,
// docs/design.md section 4). The table declares every object; the hooks below it hold the rules.
// The dictionary has checked address, access, type and range when a hook runs; a hook checks
// state only and changes nothing when it refuses (save LastError, which records why).
#include "rwmos/comp3d_module.h"

#include <array>

#include "rwmos/board_state.h"
#include "rwmos/comp3d/vectors.h"

namespace rwmos {

using objif::Access;
using objif::Address;
using objif::Entry;
using objif::ObjectInfo;
using objif::Status;
using objif::Value;
using objif::ValueType;

namespace {

constexpr double kIntMin = objif::kInt32Min;
constexpr double kIntMax = objif::kInt32Max;
constexpr double kMax = comp3d::kMaxValue;
constexpr double kLastAxis = kAxisCount - 1;
constexpr double kLastTool = comp3d::kToolCount - 1;
constexpr double kLastRow = comp3d::kCorrectionRows - 1;
constexpr auto kInt = ValueType::kInt32;
constexpr auto kDouble = ValueType::kDouble;

constexpr ObjectInfo setting(std::int32_t index, std::int32_t sub, std::string_view name,
                             ValueType type, Access access, double min, double max, Value def,
                             std::string_view rule) {
    return {comp3d::kDevSettings, index, index, sub, name, type, access, min, max, def, rule};
}
constexpr ObjectInfo tool_row(std::int32_t sub, std::string_view name, double min,
                              std::string_view rule) {
    return {comp3d::kDevTools,
            0,
            comp3d::kToolCount - 1,
            sub,
            name,
            kDouble,
            Access::kReadWrite,
            min,
            kMax,
            Value::of_double(0.0),
            rule};
}
constexpr ObjectInfo correction_row(std::int32_t sub, std::string_view name) {
    return {comp3d::kDevCorrections,
            0,
            comp3d::kCorrectionRows - 1,
            sub,
            name,
            kDouble,
            Access::kReadWrite,
            -kMax,
            kMax,
            Value::of_double(0.0),
            "[TNC-3D]: delta from the correction table, summed with tool table and TOOL CALL"};
}

double& delta_of(comp3d::Deltas& d, std::int32_t k) noexcept {
    return k == 0 ? d.dl : k == 1 ? d.dr : d.dr2;
}
double delta_of(const comp3d::Deltas& d, std::int32_t k) noexcept {
    return k == 0 ? d.dl : k == 1 ? d.dr : d.dr2;
}

}  // namespace

std::int32_t Comp3dModule::bus() const noexcept {
    return comp3d::kBus;
}
Comp3dState& Comp3dModule::s() noexcept {
    return state_.comp3d;
}

std::span<const Entry<Comp3dModule>> Comp3dModule::table() const noexcept {
    using M = Comp3dModule;
    constexpr auto kR = Access::kRead;
    constexpr auto kRW = Access::kReadWrite;
    static constexpr std::string_view kCall =
        "[TNC-3D]: delta of the TOOL CALL; taken by the next Tool write";
    static constexpr std::string_view kVectorN =
        "[TNC-3D] LN: surface normal of the next LN profile (armed with Arm)";
    static constexpr std::string_view kVectorT =
        "[TNC-3D] LN: tool vector of the next LN profile (armed with Arm)";
    static constexpr std::string_view kSum = "[TNC-3D]: tool table + TOOL CALL + correction table";
    static constexpr std::string_view kTip = "design: the last compensated tool tip (TCP)";
    static constexpr std::array<Entry<M>, 34> kTable{{
        // ---- DeviceNumber 0.
        {setting(comp3d::kIdxTool, 0, "Tool", kInt, kRW, 0, kLastTool, Value::of_int(0),
                 "[TNC-3D] TOOL CALL: loads the tool with CallDeltas; refused with a positive "
                 "oversize unless AllowOversize (M107)"),
         &M::read_tool, &M::write_tool},
        {setting(comp3d::kIdxCallDeltas, 0, "CallDL", kDouble, kRW, -kMax, kMax,
                 Value::of_double(0.0), kCall),
         &M::read_call, &M::write_call},
        {setting(comp3d::kIdxCallDeltas, 1, "CallDR", kDouble, kRW, -kMax, kMax,
                 Value::of_double(0.0), kCall),
         &M::read_call, &M::write_call},
        {setting(comp3d::kIdxCallDeltas, 2, "CallDR2", kDouble, kRW, -kMax, kMax,
                 Value::of_double(0.0), kCall),
         &M::read_call, &M::write_call},
        {setting(comp3d::kIdxCorrectionRow, 0, "CorrectionRow", kInt, kRW, 0, kLastRow,
                 Value::of_int(0), "[TNC-3D]: the correction table row in force"),
         &M::read_correction_row, &M::write_correction_row},
        {setting(comp3d::kIdxProgPath, 0, "ProgPath", kInt, kRW, 0, 1, Value::of_int(0),
                 "[TNC-3D] FUNCTION PROG PATH: 0 OFF (deltas only), 1 IS CONTOUR (full radii)"),
         &M::read_mode, &M::write_mode},
        {setting(comp3d::kIdxReference, 0, "Reference", kInt, kRW, 0, 1, Value::of_int(0),
                 "[TNC-3D] TCPM REFPNT: 0 tip, 1 centre"),
         &M::read_mode, &M::write_mode},
        {setting(comp3d::kIdxTcpm, 0, "Tcpm", kInt, kRW, 0, 1, Value::of_int(0),
                 "[TNC-3D] M128 / FUNCTION TCPM: 1 the LN's T (or N) orients the tool"),
         &M::read_mode, &M::write_mode},
        {setting(comp3d::kIdxAllowOversize, 0, "AllowOversize", kInt, kRW, 0, 1, Value::of_int(0),
                 "[TNC-3D] M107 (1) / M108 (0): 0 refused while the loaded tool is oversized"),
         &M::read_mode, &M::write_allow_oversize},
        {setting(comp3d::kIdxSide, 0, "Side", kInt, kRW, tc::kSideNone, tc::kSideRight,
                 Value::of_int(tc::kSideNone),
                 "[TNC-3D] peripheral milling: 40 R0, 41 RL, 42 RR (LN without N)"),
         &M::read_mode, &M::write_mode},
        {setting(comp3d::kIdxHeadAxisB, 0, "HeadAxisB", kInt, kRW, 0, kLastAxis, Value::of_int(4),
                 "design: board axis of the head's B (degrees), kinematics.h"),
         &M::read_mode, &M::write_mode},
        {setting(comp3d::kIdxHeadAxisC, 0, "HeadAxisC", kInt, kRW, comp3d::kNoHeadAxis, kLastAxis,
                 Value::of_int(comp3d::kNoHeadAxis),
                 "design: board axis of the head's C (degrees), -1 none"),
         &M::read_mode, &M::write_mode},
        {setting(comp3d::kIdxSurfaceNormal, 0, "NX", kDouble, kRW, -kMax, kMax,
                 Value::of_double(0.0), kVectorN),
         &M::read_vector, &M::write_vector},
        {setting(comp3d::kIdxSurfaceNormal, 1, "NY", kDouble, kRW, -kMax, kMax,
                 Value::of_double(0.0), kVectorN),
         &M::read_vector, &M::write_vector},
        {setting(comp3d::kIdxSurfaceNormal, 2, "NZ", kDouble, kRW, -kMax, kMax,
                 Value::of_double(0.0), kVectorN),
         &M::read_vector, &M::write_vector},
        {setting(comp3d::kIdxToolVector, 0, "TX", kDouble, kRW, -kMax, kMax, Value::of_double(0.0),
                 kVectorT),
         &M::read_vector, &M::write_vector},
        {setting(comp3d::kIdxToolVector, 1, "TY", kDouble, kRW, -kMax, kMax, Value::of_double(0.0),
                 kVectorT),
         &M::read_vector, &M::write_vector},
        {setting(comp3d::kIdxToolVector, 2, "TZ", kDouble, kRW, -kMax, kMax, Value::of_double(0.0),
                 kVectorT),
         &M::read_vector, &M::write_vector},
        {setting(comp3d::kIdxArm, 0, "Arm", kInt, kRW, 0, 7, Value::of_int(0),
                 "[TNC-3D] LN: bit 0 N, bit 1 T, bit 2 a line without vectors (L with RL/RR) "
                 "for the next profile; refused when a vector is not normalised"),
         &M::read_arm, &M::write_arm},
        {setting(comp3d::kIdxLastError, 0, "LastError", kInt, kRW, kIntMin, kIntMax,
                 Value::of_int(0), "design: the Refusal code of the last refusal; a write clears"),
         &M::read_last_error, &M::write_last_error},
        {setting(comp3d::kIdxDeltas, 0, "DL", kDouble, kR, -kMax, kMax, Value::of_double(0.0),
                 kSum),
         &M::read_deltas, nullptr},
        {setting(comp3d::kIdxDeltas, 1, "DR", kDouble, kR, -kMax, kMax, Value::of_double(0.0),
                 kSum),
         &M::read_deltas, nullptr},
        {setting(comp3d::kIdxDeltas, 2, "DR2", kDouble, kR, -kMax, kMax, Value::of_double(0.0),
                 kSum),
         &M::read_deltas, nullptr},
        {setting(comp3d::kIdxLastTip, 0, "LastTipX", kDouble, kR, -kMax, kMax,
                 Value::of_double(0.0), kTip),
         &M::read_last_tip, nullptr},
        {setting(comp3d::kIdxLastTip, 1, "LastTipY", kDouble, kR, -kMax, kMax,
                 Value::of_double(0.0), kTip),
         &M::read_last_tip, nullptr},
        {setting(comp3d::kIdxLastTip, 2, "LastTipZ", kDouble, kR, -kMax, kMax,
                 Value::of_double(0.0), kTip),
         &M::read_last_tip, nullptr},
        // ---- DeviceNumber 1: tool table ([TNC-3D] "Werkzeugtabelle tool.t": R, R2, DL, DR, DR2).
        {tool_row(comp3d::kSubR, "R", 0.0, "[TNC-3D]: tool radius R"), &M::read_tool_row,
         &M::write_tool_row},
        {tool_row(comp3d::kSubR2, "R2", 0.0, "[TNC-3D]: corner radius R2 (0 end mill, R ball)"),
         &M::read_tool_row, &M::write_tool_row},
        {tool_row(comp3d::kSubDl, "DL", -kMax, "[TNC-3D]: delta of the tool table on L"),
         &M::read_tool_row, &M::write_tool_row},
        {tool_row(comp3d::kSubDr, "DR", -kMax, "[TNC-3D]: delta of the tool table on R"),
         &M::read_tool_row, &M::write_tool_row},
        {tool_row(comp3d::kSubDr2, "DR2", -kMax, "[TNC-3D]: delta of the tool table on R2"),
         &M::read_tool_row, &M::write_tool_row},
        // ---- DeviceNumber 2: correction table.
        {correction_row(comp3d::kSubCorrDl, "CorrDL"), &M::read_correction, &M::write_correction},
        {correction_row(comp3d::kSubCorrDr, "CorrDR"), &M::read_correction, &M::write_correction},
        {correction_row(comp3d::kSubCorrDr2, "CorrDR2"), &M::read_correction, &M::write_correction},
    }};
    return kTable;
}

Status Comp3dModule::refuse(comp3d::Refusal r) noexcept {
    s().last_error = static_cast<std::int32_t>(r);
    return r == comp3d::Refusal::kVectorNotNormalised ? Status::kInvalidValue
                                                      : Status::kWrongDeviceState;
}

// ---- The tool in force.

Status Comp3dModule::read_tool(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(s().tool);
    return Status::kOk;
}

// [TNC-3D]: "Wenn Sie ein Werkzeug mit einem Übermaß (positive Deltawerte) einwechseln, gibt
// die Steuerung eine Fehlermeldung aus" unless M107 allows it; the tool must also exist.
Status Comp3dModule::write_tool(const ObjectInfo&, const Address&, const Value& v) {
    const std::int32_t t = v.as_int();
    const comp3d::Refusal r =
        s().check_loaded(t, s().pending_call, s().correction_row, s().allow_oversize != 0);
    if (r != comp3d::Refusal::kNone) return refuse(r);
    s().tool = t;
    s().call = s().pending_call;
    return Status::kOk;
}

Status Comp3dModule::read_call(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(delta_of(s().pending_call, a.subindex));
    return Status::kOk;
}

Status Comp3dModule::write_call(const ObjectInfo&, const Address& a, const Value& v) {
    delta_of(s().pending_call, a.subindex) = v.as_double();
    return Status::kOk;
}

Status Comp3dModule::read_correction_row(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(s().correction_row);
    return Status::kOk;
}

// The row's deltas join the sum of the loaded tool, so the loading rules apply again.
Status Comp3dModule::write_correction_row(const ObjectInfo&, const Address&, const Value& v) {
    const std::int32_t row = v.as_int();
    const comp3d::Refusal r = s().check_loaded(s().tool, s().call, row, s().allow_oversize != 0);
    if (r != comp3d::Refusal::kNone) return refuse(r);
    s().correction_row = row;
    return Status::kOk;
}

// ---- Modes (each range check is the whole rule).

std::int32_t* Comp3dModule::mode_field(std::int32_t index) noexcept {
    switch (index) {
        case comp3d::kIdxProgPath:
            return &s().prog_path;
        case comp3d::kIdxReference:
            return &s().reference;
        case comp3d::kIdxTcpm:
            return &s().tcpm;
        case comp3d::kIdxAllowOversize:
            return &s().allow_oversize;
        case comp3d::kIdxSide:
            return &s().side;
        case comp3d::kIdxHeadAxisB:
            return &s().head_axis_b;
        default:
            return &s().head_axis_c;
    }
}

Status Comp3dModule::read_mode(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_int(*mode_field(a.index));
    return Status::kOk;
}

Status Comp3dModule::write_mode(const ObjectInfo&, const Address& a, const Value& v) {
    *mode_field(a.index) = v.as_int();
    return Status::kOk;
}

// M108 while a tool with a positive oversize is loaded would leave that tool loaded against
// the rule; it is refused (call a tool without oversize first).
Status Comp3dModule::write_allow_oversize(const ObjectInfo&, const Address&, const Value& v) {
    if (v.as_int() == 0) {
        const comp3d::Refusal r = s().check_loaded(s().tool, s().call, s().correction_row, false);
        if (r == comp3d::Refusal::kPositiveOversize) return refuse(r);
    }
    s().allow_oversize = v.as_int();
    return Status::kOk;
}

// ---- The vectors of the next LN profile.

Status Comp3dModule::read_vector(const ObjectInfo&, const Address& a, Value& out) {
    const Eigen::Vector3d& v = a.index == comp3d::kIdxSurfaceNormal ? s().normal : s().tool_vector;
    out = Value::of_double(v[a.subindex]);
    return Status::kOk;
}

Status Comp3dModule::write_vector(const ObjectInfo&, const Address& a, const Value& v) {
    Eigen::Vector3d& vec = a.index == comp3d::kIdxSurfaceNormal ? s().normal : s().tool_vector;
    vec[a.subindex] = v.as_double();
    return Status::kOk;
}

Status Comp3dModule::read_arm(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(s().armed);
    return Status::kOk;
}

// [TNC-3D] "Gerade LN": "Das CAM-generierte NC-Programm muss normierte Vektoren enthalten".
Status Comp3dModule::write_arm(const ObjectInfo&, const Address&, const Value& v) {
    const std::int32_t bits = v.as_int();
    comp3d::UnitVector n;
    comp3d::UnitVector t;
    if ((bits & comp3d::kArmNormal) != 0) {
        n = comp3d::normalised(s().normal);
        if (n.refusal != comp3d::Refusal::kNone) return refuse(n.refusal);
    }
    if ((bits & comp3d::kArmToolVector) != 0) {
        t = comp3d::normalised(s().tool_vector);
        if (t.refusal != comp3d::Refusal::kNone) return refuse(t.refusal);
    }
    s().armed = bits;
    s().armed_normal = n.v;
    s().armed_tool_vector = t.v;
    return Status::kOk;
}

Status Comp3dModule::read_last_error(const ObjectInfo&, const Address&, Value& out) {
    out = Value::of_int(s().last_error);
    return Status::kOk;
}

Status Comp3dModule::write_last_error(const ObjectInfo&, const Address&, const Value&) {
    s().last_error = 0;
    return Status::kOk;
}

Status Comp3dModule::read_deltas(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(delta_of(s().summed(), a.subindex));
    return Status::kOk;
}

Status Comp3dModule::read_last_tip(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(s().last_tip[a.subindex]);
    return Status::kOk;
}

// ---- Tool table and correction table. Their values are checked when a tool is loaded and
// when a profile uses them (check_tool_load), so a table may pass through inconsistent states
// while it is written.

Status Comp3dModule::read_tool_row(const ObjectInfo&, const Address& a, Value& out) {
    const Comp3dTool& t = s().tools[static_cast<std::size_t>(a.index)];
    switch (a.subindex) {
        case comp3d::kSubR:
            out = Value::of_double(t.r);
            break;
        case comp3d::kSubR2:
            out = Value::of_double(t.r2);
            break;
        default:
            out = Value::of_double(delta_of(t.deltas, a.subindex - comp3d::kSubDl));
            break;
    }
    return Status::kOk;
}

Status Comp3dModule::write_tool_row(const ObjectInfo&, const Address& a, const Value& v) {
    Comp3dTool& t = s().tools[static_cast<std::size_t>(a.index)];
    switch (a.subindex) {
        case comp3d::kSubR:
            t.r = v.as_double();
            break;
        case comp3d::kSubR2:
            t.r2 = v.as_double();
            break;
        default:
            delta_of(t.deltas, a.subindex - comp3d::kSubDl) = v.as_double();
            break;
    }
    return Status::kOk;
}

Status Comp3dModule::read_correction(const ObjectInfo&, const Address& a, Value& out) {
    out = Value::of_double(delta_of(s().corrections[static_cast<std::size_t>(a.index)],
                                    a.subindex - comp3d::kSubCorrDl));
    return Status::kOk;
}

Status Comp3dModule::write_correction(const ObjectInfo&, const Address& a, const Value& v) {
    delta_of(s().corrections[static_cast<std::size_t>(a.index)], a.subindex - comp3d::kSubCorrDl) =
        v.as_double();
    return Status::kOk;
}

}  // namespace rwmos
