// SPDX-License-Identifier: MIT
#include "rwmos/tc_state.h"

#include "objif/enum_names.h"

namespace rwmos {

geom::PlaneAxes plane_axes(const TcState& tc) noexcept {
    const auto& nr = tc.axis_nr;
    return geom::board_axes(geom::plane_from_code(tc.plane).value_or(geom::Plane::kXY),
                            {nr[0], nr[1], nr[2]});
}

std::int32_t active_group(const TcState& tc) noexcept {
    const geom::PlaneAxes p = plane_axes(tc);
    if (p.first == p.second) return 0;
    for (std::int32_t n = 1; n <= tc::kGroupCount; ++n) {
        const TcGroup& g = tc.group(n);
        if ((g.x_axis == p.first && g.y_axis == p.second) ||
            (g.x_axis == p.second && g.y_axis == p.first))
            return n;
    }
    return 0;
}

namespace {
bool uses_axis(const TcGroup& g, std::int32_t axis) noexcept {
    return g.x_axis == axis || g.y_axis == axis || g.z_axis == axis;
}
}  // namespace

InitFault initialisation_fault(const TcState& tc, std::int32_t group) noexcept {
    const TcGroup& g = tc.group(group);
    if (g.x_axis == g.y_axis || g.x_axis == g.z_axis || g.y_axis == g.z_axis)
        return InitFault::kAxesNotDistinct;
    if (g.side == tc::kSideNone) return InitFault::kNoSide;
    for (std::int32_t n = 1; n <= tc::kGroupCount; ++n) {
        if (n == group || !tc.group(n).running()) continue;
        const TcGroup& other = tc.group(n);
        if (uses_axis(other, g.x_axis) || uses_axis(other, g.y_axis) || uses_axis(other, g.z_axis))
            return InitFault::kAxisInUse;
    }
    return InitFault::kNone;
}

std::string_view init_fault_message(InitFault f) noexcept {
    static constexpr auto kMessages = objif::enum_names<InitFault::kNone, InitFault::kAxisInUse>(
        {"initialised", "XAxis, YAxis and ZAxis must name three different board axes",
         "no compensation side selected: write Left or Right first",
         "another running compensation group uses one of these axes"},
        "unknown");
    return kMessages(f);
}

}  // namespace rwmos
