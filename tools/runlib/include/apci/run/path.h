// SPDX-License-Identifier: MIT
// The executed path as `apcictl run` reports it (docs/design.md section 7): segments of the tool
// centre path and of the programmed contour, in program coordinates X, Y, Z (mm), each tagged
// with the NC block it came from; the errors of a run; the TC registers at its end.
#pragma once

#include <Eigen/Core>
#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>

#include "geometry/plane.h"

namespace apci::run {

using Point = Eigen::Vector3d;

// JSON "kind".
enum class SegmentKind : std::uint8_t { kRapid = 0, kLine = 1, kArc = 2 };
std::string_view kind_name(SegmentKind k) noexcept;  // "rapid", "line", "arc"

// JSON "role". Rapid moves are "uncompensated" (the TC module never compensates G00).
enum class Role : std::uint8_t {
    kContour = 0,        // a compensated G01/G02/G03 element
    kTransition = 1,     // the transition at an outside corner
    kApproach = 2,       // onto the compensated path
    kDeparture = 3,      // from the compensated path back to the programmed end point
    kUncompensated = 4,  // G00, or G01/G02/G03 without radius compensation
};
std::string_view role_name(Role r) noexcept;  // "contour", "transition", ...

// The NC block a segment or error belongs to: its N number, or kNoBlock when the block has
// none (then `line` says which source line it was, when known; 0 = unknown).
inline constexpr std::int64_t kNoBlock = -1;
struct BlockRef {
    std::int64_t number = kNoBlock;
    std::uint64_t line = 0;
};

// Planes by their G codes (TcPlane values): 17 X-Y, 18 Z-X, 19 Y-Z; their axes as indices
// into X, Y, Z (geometry/plane.h).
using geom::PlaneAxes;
// f(first, second, third) with the axes of a plane, each a std::integral_constant (an index
// into X, Y, Z known when the code is compiled): {0,1,2} for 17, {2,0,1} for 18, {1,2,0} for 19;
// 17's for anything else.
template <class F>
[[gnu::always_inline]] constexpr decltype(auto) with_plane_axes(int plane, F&& f) {
    using std::integral_constant;
    switch (plane) {
        case 18:
            return f(integral_constant<int, 2>{}, integral_constant<int, 0>{},
                     integral_constant<int, 1>{});
        case 19:
            return f(integral_constant<int, 1>{}, integral_constant<int, 2>{},
                     integral_constant<int, 0>{});
        default:
            return f(integral_constant<int, 0>{}, integral_constant<int, 1>{},
                     integral_constant<int, 2>{});
    }
}
// with_plane_axes hands out the shared geometry's axes (geometry/plane.h), as constants.
static_assert([] {
    for (const geom::Plane p : {geom::Plane::kXY, geom::Plane::kZX, geom::Plane::kYZ}) {
        const geom::PlaneAxes a = geom::plane_axes(p);
        if (!with_plane_axes(static_cast<int>(p), [&](int first, int second, int third) {
                return first == a.first && second == a.second && third == a.third;
            }))
            return false;
    }
    return true;
}());
// The same axes as values (17's for anything but 18 and 19).
constexpr PlaneAxes plane_axes(int plane) noexcept {
    return geom::plane_axes(plane == 18 ? geom::Plane::kZX
                            : plane == 19 ? geom::Plane::kYZ
                                          : geom::Plane::kXY);
}
// "X-Y", "Z-X", "Y-Z".
std::string_view plane_name(int plane) noexcept;
char axis_letter(int axis) noexcept;  // 'X', 'Y', 'Z'

struct PathSegment {
    BlockRef block;
    SegmentKind kind = SegmentKind::kLine;
    Role role = Role::kUncompensated;
    Point start = Point::Zero();
    Point end = Point::Zero();
    // Arcs only: centre (its coordinate on the plane's third axis is the start's), sense seen
    // from the positive third axis, and the plane (17, 18, 19). start == end in the plane is a
    // full circle.
    Point center = Point::Zero();
    bool ccw = false;
    int plane = 17;
    // Executed segments: the interpolation cycles it ran in (start_cycle, end_cycle];
    // 0, 0 for programmed moves.
    std::uint64_t start_cycle = 0;
    std::uint64_t end_cycle = 0;
    // Executed segments: an arc's sweep (arc_sweep; 0 for a line) and the length
    // (segment_length), computed once where the executor makes the segment (measure()), so
    // the totals and the plot do not compute them again; NaN where not measured (programmed
    // moves): computed where needed.
    double sweep = std::numeric_limits<double>::quiet_NaN();
    double length = std::numeric_limits<double>::quiet_NaN();
};

// Two points this close in the plane are one point (an arc between them is a full circle).
inline constexpr double kSamePointTolerance = 1e-9;

// The same bits, not only equal values: -0 and 0 apart, a NaN the same as itself with its
// payload (what a writer keeps of a number it gives back, or writes once for both).
inline bool same_bits(double a, double b) noexcept {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
inline bool same_bits(const Point& a, const Point& b) noexcept {
    return same_bits(a[0], b[0]) && same_bits(a[1], b[1]) && same_bits(a[2], b[2]);
}

// Signed angle an arc turns through, counter-clockwise positive, magnitude in (0, 2 pi].
double arc_sweep(const PathSegment& arc) noexcept;
// Radius of an arc at its start, and at its end (they differ by rounding at most: the arc's
// radius changes linearly with the angle, as the board runs it).
double arc_radius(const PathSegment& arc) noexcept;
double arc_end_radius(const PathSegment& arc) noexcept;
// The point at fraction t (0..1) of the way along a segment (arcs by angle with the radius
// interpolated, helix-linear in the third axis).
Point point_along(const PathSegment& s, double t) noexcept;
// Length in space: chord of a line or rapid, helix length of an arc.
double segment_length(const PathSegment& s) noexcept;
// Sets s.sweep and s.length (the same values as arc_sweep and segment_length).
void measure(PathSegment& s) noexcept;
// s.sweep when measured, else arc_sweep(s); s.length when measured, else segment_length(s).
double measured_sweep(const PathSegment& s) noexcept;
double measured_length(const PathSegment& s) noexcept;
// True when a programmed move certainly takes at most nc::kMaxMoveCycles interpolation cycles
// of `cycle_seconds` at `feed` mm/min, told as nc::surely_within_move_cycles tells it (no root
// or angle); false decides nothing: nc::check_move_cycles of segment_length() then does.
bool surely_within_move_cycles(const PathSegment& s, double feed, double cycle_seconds) noexcept;

// A turning tool's compensated segment (the board carries the nose centre's path over to the
// imaginary tip, objif/map/cutting_edge.h) taken back to the nose centre: `edge` (the tip from the
// centre, plane coordinates {first, second}) off what the board carried over, by the segment's
// role as the board does it: a contour element and a transition whole, an approach its end (an
// approach arc whole), a departure its start. Other roles and a zero edge: s unchanged.
PathSegment nose_centre_path(const PathSegment& s, const Eigen::Vector2d& edge, int plane) noexcept;

// One error of a run: from the board (code = the Table 4 bit name, e.g. "KorrError", or a
// status name such as "InvalidValue") or from the program's execution pass (code = the
// apci_nc error kind name).
struct RunError {
    BlockRef block;
    std::string code;
    std::string message;
};

// ERROR and STATUS of one compensation group (bus 1300, DeviceNumber 1, Index `group`) at the
// end of the run; `readable` false when the board could not be asked (e.g. no optionTC).
struct GroupRegisters {
    int group = 0;
    bool readable = false;
    std::int32_t error = 0;
    std::int32_t status = 0;
};

}  // namespace apci::run
