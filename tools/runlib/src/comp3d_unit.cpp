// SPDX-License-Identifier: MIT
#include "comp3d_unit.h"

#include <fmt/format.h>

#include <utility>

#include "run_context.h"
#include "objif/map/comp3d_refusal.h"
#include "objif/map/object_map.h"

namespace apci::run::exec {

namespace {

namespace tc = objif::map::tc;
namespace c3 = objif::map::comp3d;

// The correction table's rows and values fit the 3D module's table (DeviceNumber 2).
static_assert(nc::kMaxCorrectionRow == objif::map::comp3d::kCorrectionRows - 1);
static_assert(nc::kCorrectionLimit == objif::map::comp3d::kMaxValue);

ObjectDescriptor c3_object(std::int32_t index, std::int32_t sub = 0) noexcept {
    return apci::object(c3::kBus, c3::kDevSettings, index, sub);
}

}  // namespace

// ---- Klartext 3D compensation (bus 1310; docs/apcictl.md "run", docs/object-map.md 6)

// The first Klartext 3D event puts the module in the program's start state: no tool, no
// deltas, PROG PATH OFF, TCPM off (tip), M108, R0, nothing armed; the head's B and C on the
// board axes the run placed them on (RunContext::setup).
bool Comp3dUnit::setup(const BlockRef& at) {
    if (ready_) return true;
    auto probe = c3_object(c3::kIdxTool);
    if (run_.board().read_int(probe).status == APCI_NO_SUCH_DEVICE) {
        return run_.record(at, "NoSuchDevice",
                           "Klartext LN lines, TOOL CALL deltas, TCPM and PROG PATH need the 3D "
                           "compensation module (bus 1310), which this board does not have");
    }
    ready_ = true;
    const std::pair<std::int32_t, std::int32_t> settings[] = {
        {c3::kIdxAllowOversize, 1},
        {c3::kIdxTool, 0},
        {c3::kIdxCorrectionRow, 0},
        {c3::kIdxAllowOversize, 0},
        {c3::kIdxProgPath, 0},
        {c3::kIdxReference, 0},
        {c3::kIdxTcpm, 0},
        {c3::kIdxSide, 40},
        {c3::kIdxArm, 0},
        {c3::kIdxHeadAxisB, run_.head().b_axis},
        {c3::kIdxHeadAxisC, run_.head().c_axis}};
    for (int k = 0; k < 3; ++k) {
        auto o = c3_object(c3::kIdxCallDeltas, k);
        if (!write(o, 0.0, at, "CallDeltas")) return false;
    }
    for (const auto& [index, value] : settings) {
        auto o = c3_object(index);
        if (!write(o, value, at, "3D compensation setup")) return false;
    }
    // The correction table: row 0 (FUNCTION CORRDATA RESET TCS, the start) without
    // correction, then the rows of --corr.
    if (!correction_row(at, nc::CorrectionRow{})) return false;
    if (corrections_ != nullptr)
        for (const nc::CorrectionRow& r : corrections_->rows())
            if (!correction_row(at, r)) return false;
    return true;
}

bool Comp3dUnit::correction_row(const BlockRef& at, const nc::CorrectionRow& r) {
    const std::pair<std::int32_t, double> values[] = {
        {c3::kSubCorrDl, r.dl}, {c3::kSubCorrDr, r.dr}, {c3::kSubCorrDr2, r.dr2}};
    for (const auto& [sub, value] : values) {
        auto o = apci::object(c3::kBus, c3::kDevCorrections, r.row, sub);
        if (!write(o, value, at, "correction table")) return false;
    }
    return true;
}

bool Comp3dUnit::setting(const BlockRef& at, std::int32_t index, std::int32_t value,
                         std::string_view what) {
    if (!setup(at)) return false;
    auto o = c3_object(index);
    return write(o, value, at, what);
}

// TOOL CALL n Z DL DR DR2: the tool list's R, R2 and deltas into the module's tool table
// row n, the call's deltas, then Tool = n (the board checks the oversize rule).
bool Comp3dUnit::tool_call(const BlockRef& at, const nc::ToolCallDeltas& e) {
    if (!setup(at)) return false;
    const nc::ToolData* t =
        run_.tools() != nullptr && e.tool > 0 ? run_.tools()->find(e.tool) : nullptr;
    const double row[] = {t ? t->radius_mm() : 0.0, t ? t->r2_mm() : 0.0, t ? t->dl_mm() : 0.0,
                          t ? t->dr_mm() : 0.0, t ? t->dr2_mm() : 0.0};
    for (std::int32_t sub = c3::kSubR; sub <= c3::kSubDr2; ++sub) {
        auto o = apci::object(c3::kBus, c3::kDevTools, e.tool, sub);
        if (!write(o, row[sub - c3::kSubR], at, "tool table")) return false;
    }
    const double call[] = {e.dl, e.dr, e.dr2};
    for (int k = 0; k < 3; ++k) {
        auto o = c3_object(c3::kIdxCallDeltas, k);
        if (!write(o, call[k], at, "CallDeltas")) return false;
    }
    auto o = c3_object(c3::kIdxTool);
    return write(o, std::int32_t{e.tool}, at, "TOOL CALL");
}

// M128 / FUNCTION TCPM / M129 / FUNCTION RESET TCPM. Lines with RL/RR under TCPM are the 3D
// module's (peripheral milling), so a 2D radius compensation under way ends first.
bool Comp3dUnit::tcpm(const BlockRef& at, const nc::TcpmChange& e) {
    if (e.on && run_.tc_unit().state().comp_on && !run_.tc_unit().compensation_off(at)) return false;
    if (!setting(at, c3::kIdxReference, e.reference == nc::ToolReference::kCentre ? 1 : 0,
                 "Reference") ||
        !setting(at, c3::kIdxTcpm, e.on ? 1 : 0, "Tcpm"))
        return false;
    tcpm_ = e.on;
    return true;
}

// R0 / RL / RR of a Klartext program: the 3D module's side (LN lines, and L lines under
// TCPM); without TCPM an L line's RL/RR is the TC module's 2D radius compensation.
bool Comp3dUnit::compensation(const BlockRef& at, nc::Compensation side) {
    side_ = side;
    const std::int32_t code = side == nc::Compensation::kLeft    ? tc::kSideLeft
                              : side == nc::Compensation::kRight ? tc::kSideRight
                                                                 : tc::kSideNone;
    if (!setting(at, c3::kIdxSide, code, "Side")) return false;
    if (tcpm_) return true;
    return run_.tc_unit().compensation(at, side);
}

// L .. B.. C..: the head's axes, which the module reads for the tool direction.
bool Comp3dUnit::head(const BlockRef& at, const nc::HeadOrientation& e) {
    return setup(at) && run_.head_turn(at, e);
}

// LN: N and T into the module, armed, then the line as a G01 profile; the board puts the
// compensated tool tip into its end point.
bool Comp3dUnit::vector_line(const BlockRef& at, const nc::VectorLineMove& e) {
    if (!setup(at)) return false;
    std::int32_t bits = 0;
    if (e.has_normal) {
        for (int k = 0; k < 3; ++k) {
            auto o = c3_object(c3::kIdxSurfaceNormal, k);
            if (!write(o, e.normal[k], at, "SurfaceNormal")) return false;
        }
        bits |= c3::kArmNormal;
    }
    // Without TCPM a programmed T is ignored ([TNC-3D]); with TCPM and no T the board
    // takes N.
    if (e.has_tool_vector && e.tool_vector_programmed) {
        for (int k = 0; k < 3; ++k) {
            auto o = c3_object(c3::kIdxToolVector, k);
            if (!write(o, e.tool_vector[k], at, "ToolVector")) return false;
        }
        bits |= c3::kArmToolVector;
    }
    if (bits == 0) bits = c3::kArmLine;
    auto arm = c3_object(c3::kIdxArm);
    if (!write(arm, bits, at, "Arm")) return false;
    const PathSegment s = RunContext::line_segment(at, SegmentKind::kLine, e.start, e.end);
    return spool(at, s,
                 run_.profile(at, APCI_PROFILE_LINE, e.end, e.rapid ? kRapidFeed : e.feed));
}

// A profile for the 3D module: its refusal is named by the module's LastError.
bool Comp3dUnit::spool(const BlockRef& at, const PathSegment& programmed,
                       const apci_profile& p) {
    run_.programmed(programmed, p.tag);
    run_.head_spooled();
    apci::Result<apci_motion_result> r;
    if (!run_.spool_profile(p, r)) return false;
    if (r.ok()) return true;
    return failure(at, r.status, "LN");
}

template <typename T>
bool Comp3dUnit::write(ObjectDescriptor o, T value, const BlockRef& at, std::string_view what) {
    const auto r = run_.board().write(o, value);
    if (r.ok()) return true;
    return failure(at, r.status, what);
}

// The module's LastError names a refusal (objif::map::comp3d::Refusal); it is cleared for the
// next one.
bool Comp3dUnit::failure(const BlockRef& at, apci::Status status, std::string_view what) {
    const std::string text = run_.failure_words(what);
    auto last = c3_object(c3::kIdxLastError);
    const auto code = run_.board().read_int(last);
    if (code && code.value != 0) {
        auto clear = c3_object(c3::kIdxLastError);
        (void)run_.board().write(clear, std::int32_t{0});
        const auto refusal = static_cast<c3::Refusal>(code.value);
        return run_.record(at, std::string(c3::refusal_name(refusal)),
                           fmt::format("{} ({})", text, c3::refusal_message(refusal)));
    }
    return run_.record(at, std::string(apci::status_name(status)), text);
}

}  // namespace apci::run::exec
