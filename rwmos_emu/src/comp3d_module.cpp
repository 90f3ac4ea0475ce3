// SPDX-License-Identifier: MIT
// 3D tool compensation module, bus 1310 ([TNC-3D]; design numbers,
// docs/design.md section 4). The table declares every object; the hooks below it hold the rules.
// The dictionary has checked address, access, type and range when a hook runs; a hook checks
// state only and changes nothing when it refuses (save LastError, which records why).
#include "rwmos/comp3d_module.h"

#include <array>

#include "objif/map/objects.h"

#include "rwmos/board_state.h"
#include "rwmos/comp3d/vectors.h"
#include "rwmos/module_table.h"

namespace rwmos {

namespace {

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
    static constexpr std::array<Hooks<M>, 34> kHooks{{
        // ---- DeviceNumber 0.
        {"Tool", &M::read_field<&State::comp3d, &Comp3dState::tool>, &M::write_tool},
        {"CallDL", &M::read_call, &M::write_call},
        {"CallDR", &M::read_call, &M::write_call},
        {"CallDR2", &M::read_call, &M::write_call},
        {"CorrectionRow", &M::read_field<&State::comp3d, &Comp3dState::correction_row>,
         &M::write_correction_row},
        {"ProgPath", &M::read_field<&State::comp3d, &Comp3dState::prog_path>,
         &M::write_field<&State::comp3d, &Comp3dState::prog_path>},
        {"Reference", &M::read_field<&State::comp3d, &Comp3dState::reference>,
         &M::write_field<&State::comp3d, &Comp3dState::reference>},
        {"Tcpm", &M::read_field<&State::comp3d, &Comp3dState::tcpm>,
         &M::write_field<&State::comp3d, &Comp3dState::tcpm>},
        {"AllowOversize", &M::read_field<&State::comp3d, &Comp3dState::allow_oversize>,
         &M::write_allow_oversize},
        {"Side", &M::read_field<&State::comp3d, &Comp3dState::side>,
         &M::write_field<&State::comp3d, &Comp3dState::side>},
        {"HeadAxisB", &M::read_field<&State::comp3d, &Comp3dState::head_axis_b>,
         &M::write_field<&State::comp3d, &Comp3dState::head_axis_b>},
        {"HeadAxisC", &M::read_field<&State::comp3d, &Comp3dState::head_axis_c>,
         &M::write_field<&State::comp3d, &Comp3dState::head_axis_c>},
        {"NX", &M::read_vector, &M::write_vector},
        {"NY", &M::read_vector, &M::write_vector},
        {"NZ", &M::read_vector, &M::write_vector},
        {"TX", &M::read_vector, &M::write_vector},
        {"TY", &M::read_vector, &M::write_vector},
        {"TZ", &M::read_vector, &M::write_vector},
        {"Arm", &M::read_field<&State::comp3d, &Comp3dState::armed>, &M::write_arm},
        {"LastError", &M::read_field<&State::comp3d, &Comp3dState::last_error>,
         &M::write_last_error},
        {"DL", &M::read_deltas, nullptr},
        {"DR", &M::read_deltas, nullptr},
        {"DR2", &M::read_deltas, nullptr},
        {"LastTipX", &M::read_last_tip, nullptr},
        {"LastTipY", &M::read_last_tip, nullptr},
        {"LastTipZ", &M::read_last_tip, nullptr},
        // ---- DeviceNumber 1: tool table ([TNC-3D] "Werkzeugtabelle tool.t": R, R2, DL, DR, DR2).
        {"R", &M::read_tool_row, &M::write_tool_row},
        {"R2", &M::read_tool_row, &M::write_tool_row},
        {"DL", &M::read_tool_row, &M::write_tool_row},
        {"DR", &M::read_tool_row, &M::write_tool_row},
        {"DR2", &M::read_tool_row, &M::write_tool_row},
        // ---- DeviceNumber 2: correction table.
        {"CorrDL", &M::read_correction, &M::write_correction},
        {"CorrDR", &M::read_correction, &M::write_correction},
        {"CorrDR2", &M::read_correction, &M::write_correction},
    }};
    static constexpr auto kTable = objif::attach(objif::map::comp3d::kObjects, kHooks);
    return kTable;
}

Status Comp3dModule::refuse(comp3d::Refusal r) noexcept {
    s().last_error = static_cast<std::int32_t>(r);
    return r == comp3d::Refusal::kVectorNotNormalised ? Status::kInvalidValue
                                                      : Status::kWrongDeviceState;
}

// ---- The tool in force.

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

// The row's deltas join the sum of the loaded tool, so the loading rules apply again.
Status Comp3dModule::write_correction_row(const ObjectInfo&, const Address&, const Value& v) {
    const std::int32_t row = v.as_int();
    const comp3d::Refusal r = s().check_loaded(s().tool, s().call, row, s().allow_oversize != 0);
    if (r != comp3d::Refusal::kNone) return refuse(r);
    s().correction_row = row;
    return Status::kOk;
}

// ---- Modes: the table's range check is the whole rule (read_field, write_field), but for
// AllowOversize.

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
