// SPDX-License-Identifier: MIT
#include "tc_unit.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "run_context.h"
#include "objif/map/cutting_edge.h"

namespace apci::run::exec {

namespace {

namespace tc = objif::map::tc;

// The plane each group compensates in (group g serves plane kGroupPlane[g - 1]).
constexpr std::array<int, kGroups> kGroupPlane{17, 18, 19};

}  // namespace

// RESET (every group to power-on), then group g in the plane kGroupPlane[g - 1], and the
// program's start state: G17, the NC start corner mode (G25; the board's own default is
// circular) and selection method (G139; the board's own is perpendicular, G237), and the tool
// length on every move from the tool's selection on, as NC controls apply it, DIN and Klartext
// alike (LengthMode 1; the board's own applies it while compensating). Only #TRAFO changes that
// (length_mode).
bool TcUnit::setup() {
    auto reset = group_object(1, tc::kSubReset);
    if (!run_.write(reset, std::int32_t{1}, {}, "RESET")) return false;
    for (std::int32_t g = 1; g <= kGroups; ++g) {
        const PlaneAxes p = plane_axes(kGroupPlane[static_cast<std::size_t>(g - 1)]);
        auto x = group_object(g, tc::kSubXAxis);
        auto y = group_object(g, tc::kSubYAxis);
        auto z = group_object(g, tc::kSubZAxis);
        auto corner = group_object(g, tc::kSubCornerMode);
        auto selection = group_object(g, tc::kSubSelectionMode);
        auto length = group_object(g, tc::kSubLengthMode);
        if (!run_.write(x, run_.axis(p.first), {}, "XAxis") ||
            !run_.write(y, run_.axis(p.second), {}, "YAxis") ||
            !run_.write(z, run_.axis(p.third), {}, "ZAxis") ||
            !run_.write(corner, std::int32_t{nc::g_number(nc::kStartCornerMode)}, {},
                        "CornerMode") ||
            !run_.write(selection, std::int32_t{nc::g_number(nc::kStartSelectionMode)}, {},
                        "SelectionMode") ||
            !run_.write(length, tc::kLengthAlways, {}, "LengthMode"))
            return false;
    }
    state_.length_always = true;
    auto plane = init_object(tc::kIdxTcPlane);
    return run_.write(plane, std::int32_t{17}, {}, "TcPlane");
}

void TcUnit::read_registers() {
    for (std::int32_t g = 1; g <= kGroups; ++g) {
        GroupRegisters r;
        r.group = g;
        auto e = group_object(g, tc::kSubError);
        auto s = group_object(g, tc::kSubStatus);
        const auto error = run_.board().read_int(e);
        const auto status = run_.board().read_int(s);
        r.readable = error.ok() && status.ok();
        r.error = error.value_or(0);
        r.status = status.value_or(0);
        run_.outcome().registers.push_back(r);
    }
}

bool TcUnit::tool(const BlockRef& at, int index) {
    if (run_.outcome().otc_present && !run_.otc_unit().change_tool(at, index)) return false;
    state_.current_tool = index;
    if (!run_.outcome().tc_present) return true;  // no TC module: nothing takes a tool
    const nc::ToolData* t =
        run_.tools() != nullptr && index > 0 ? run_.tool_list().find(index) : nullptr;
    const double radius = t != nullptr ? t->radius_mm() : 0.0;
    const double length = t != nullptr ? t->length_mm() : 0.0;
    // A turning tool's cutting edge position (srk_lage, ISG P-TOOL-00002): the board carries
    // the compensated nose centre over to the imaginary tip (docs/compensation.md).
    const std::int32_t edge = t != nullptr ? t->srk_lage : 0;
    // A tool change: the axes stop first, so every segment read back so far ran with the
    // old tool's length.
    if (!run_.run_clock()) return false;
    for (std::int32_t g = 1; g <= kGroups; ++g) {
        auto index_object = group_object(g, tc::kSubWkzIndex);
        auto radius_object = group_object(g, tc::kSubRadius);
        auto length_object = group_object(g, tc::kSubWkzLen);
        auto edge_object = group_object(g, tc::kSubCuttingEdge);
        if (!run_.write(index_object, std::int32_t{index}, at, "WKZINDEX") ||
            !run_.write(radius_object, radius, at, "RADIUS") ||
            !run_.write(length_object, length, at, "WkzLen") ||
            !run_.write(edge_object, edge, at, "CuttingEdge"))
            return false;
    }
    state_.length = length;
    state_.radius = radius;
    state_.cutting_edge = edge;
    return true;
}

bool TcUnit::plane(const BlockRef& at, nc::Plane p) {
    if (!run_.outcome().tc_present) {
        state_.plane = nc::g_number(p);
        return true;
    }
    // The length axis changes with the plane: the segments that ran in the old one are read
    // first, in the old one.
    if (!run_.run_clock()) return false;
    state_.plane = nc::g_number(p);
    auto o = init_object(tc::kIdxTcPlane);
    return run_.write(o, std::int32_t{state_.plane}, at, "TcPlane");
}

bool TcUnit::corner(const BlockRef& at, nc::CornerMode m) {
    return every_group(at, tc::kSubCornerMode, nc::g_number(m), "CornerMode");
}

bool TcUnit::selection(const BlockRef& at, nc::SelectionMode m) {
    return every_group(at, tc::kSubSelectionMode, nc::g_number(m), "SelectionMode");
}

bool TcUnit::length_mode(const BlockRef& at, bool always) {
    if (!run_.outcome().tc_present || always == state_.length_always) return true;
    if (!run_.run_clock()) return false;
    if (!every_group(at, tc::kSubLengthMode, always ? tc::kLengthAlways : tc::kLengthWhileCompensating,
                     "LengthMode"))
        return false;
    state_.length_always = always;
    return true;
}

bool TcUnit::read_length() {
    auto len = group_object(1, tc::kSubWkzLen);
    const auto l = run_.board().read_double(len);
    if (l) state_.length = l.value;
    return l.ok();
}

bool TcUnit::every_group(const BlockRef& at, std::int32_t sub, std::int32_t value,
                         std::string_view what) {
    if (!run_.outcome().tc_present) return true;
    for (std::int32_t g = 1; g <= kGroups; ++g) {
        auto o = group_object(g, sub);
        if (!run_.write(o, value, at, what)) return false;
    }
    return true;
}

bool TcUnit::compensation(const BlockRef& at, nc::Compensation side) {
    if (!run_.outcome().tc_present) {
        return run_.record(at, "NoSuchDevice",
                           fmt::format("G{} needs the TC module (bus 1300), and this board's "
                                       "firmware has no optionTC",
                                       nc::g_number(side)));
    }
    if (state_.comp_on && !compensation_off(at)) return false;
    if (side == nc::Compensation::kOff) return true;
    auto select = group_object(tc::kActiveGroupIndex,
                               side == nc::Compensation::kLeft ? tc::kSubLeft : tc::kSubRight);
    auto status = group_object(tc::kActiveGroupIndex, tc::kSubStatus);
    if (!run_.write(select, std::int32_t{1}, at,
                    side == nc::Compensation::kLeft ? "Left" : "Right") ||
        !run_.write(status, std::int32_t{1}, at, "STATUS = 1"))
        return false;
    state_.comp_on = true;
    notice_small_radius(at, side);
    state_.comp_plane = state_.plane;
    state_.comp_side = side == nc::Compensation::kLeft ? 1 : -1;
    // A turning tool's path is its imaginary tip; the check measures the nose centre.
    const auto edge = tc::cutting_edge_offset(state_.cutting_edge, state_.radius);
    run_.begin_stretch(CompensatedStretch{state_.radius, state_.comp_plane, state_.comp_side,
                                          Eigen::Vector2d(edge[0], edge[1])});
    if (!state_.comp_plane_seen) {
        state_.comp_plane_seen = true;
        run_.outcome().plot_plane = state_.plane;
    }
    return true;
}

// G41/G42 with no radius runs the programmed contour itself, as a control does (CAM programs
// for wear-only offsets select a register holding 0): said once per tool, naming why.
void TcUnit::notice_small_radius(const BlockRef& at, nc::Compensation side) {
    if (std::abs(state_.radius) >= kLeastRadius) return;
    const int tool = state_.current_tool;
    if (std::find(small_radius_tools_.begin(), small_radius_tools_.end(), tool) !=
        small_radius_tools_.end())
        return;
    small_radius_tools_.push_back(tool);
    const nc::ToolData* t =
        run_.tools() != nullptr && tool > 0 ? run_.tool_list().find(tool) : nullptr;
    const int g = nc::g_number(side);
    std::string text;
    if (tool <= 0)
        text = fmt::format("G{} with no tool selected (no D word yet, or D0) compensates by radius "
                           "0: the path is the programmed contour; select the tool with D n",
                           g);
    else if (state_.radius == 0.0)
        text = fmt::format("G{} with tool {}, whose radius is 0, compensates by nothing: the path "
                           "is the programmed contour",
                           g, tool);
    else
        text = fmt::format("G{} with tool {} compensates by {:g} mm only{}", g, tool,
                           state_.radius,
                           t != nullptr && t->mass_einheit == 0
                               ? fmt::format(": the tool list gives lengths in 0.1 um unless "
                                             "wz[{}].mass_einheit is 1 (radius 50000 is 5 mm)",
                                             tool)
                               : std::string{});
    run_.outcome().notices.push_back(RunError{at, "NoRadius", std::move(text)});
}

// STATUS = 0: the held profile is spooled ([APCI-TC] section 1); under G237 with the
// departure, under G139 without: the G40 block's move departs (docs/compensation.md).
bool TcUnit::compensation_off(const BlockRef& at) {
    auto status = group_object(tc::kActiveGroupIndex, tc::kSubStatus);
    if (!run_.write(status, std::int32_t{0}, at, "STATUS = 0")) return false;
    state_.comp_on = false;
    return run_.end_stretch();
}

}  // namespace apci::run::exec
