// SPDX-License-Identifier: MIT
// What the host hands the board's motion part (profiles, direct commands, SSF
// commands) and what it can observe (executed segments, per-cycle samples).
// docs/motion.md is the spec page.
//
// Units: positions in interpolation units (a double per axis), feed in
// interpolation units per minute (F of DIN 66025), time in interpolation
// cycles (the cycle length is the board's interpolation-cycle object).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "objif/map/limits.h"
#include "objif/status.h"
#include "rwmos/geometry/shared.h"

namespace rwmos::motion {

inline constexpr int kAxisCount = 8;
using AxisVector = std::array<double, kAxisCount>;
using AxisMask = std::uint8_t;  // bit i = board axis i
inline constexpr AxisMask kAllAxes = 0xFF;

// Feed of a rapid (G00) or JA move that names no feed (feed 0): design.
inline constexpr double kDefaultRapidFeed = objif::map::kRapidFeed;  // units/min = 1 unit per ms
// Upper bound of any feed: keeps cycle counts and positions finite. Design.
inline constexpr double kMaxFeed = 1.0e9;
// Upper bound of any coordinate's magnitude: the compensation geometry's
// (geometry/tolerances.h), so every profile can be compensated.
inline constexpr double kMaxCoordinate = geom::kMaxCoordinate;
// The geometry library stands alone (Eigen only): its bound is the board's, declared in objif.
static_assert(geom::kMaxCoordinate == objif::map::kMaxCoordinate);

// G00 / G01 / G02 / G03, and the traverse (design, an extension): a G00 that the TC module
// treats as an interpolation profile, compensated and rotated as a G01 at the rapid feed (feed
// 0: kDefaultRapidFeed), as NC controls compensate a G00 under G41/G42; its moves are rapid
// ones for everything else (OTC wears nothing on them, [ISG-OTC] section 2: "Eilgangssätze
// sind verschleißfrei!"). The numeric values travel on the wire.
enum class ProfileKind : std::uint8_t { kRapid = 0, kLine = 1, kArcCw = 2, kArcCcw = 3, kTraverse = 4 };
std::string_view profile_kind_name(ProfileKind k) noexcept;  // "G00" ...
// Profiles whose feed may be 0 (the rapid feed) and whose moves are rapid traverses.
constexpr bool is_rapid(ProfileKind k) noexcept {
    return k == ProfileKind::kRapid || k == ProfileKind::kTraverse;
}
constexpr bool is_interpolation(ProfileKind k) noexcept {
    return k != ProfileKind::kRapid;
}
constexpr bool is_arc(ProfileKind k) noexcept {
    return k == ProfileKind::kArcCw || k == ProfileKind::kArcCcw;
}

// One spooled motion profile (one NC block's move). Members ordered by size
// (no padding inside; the spooler holds 256 of them per group).
struct Profile {
    // Interpolation units per minute along the path; > 0 for G01..G03.
    // G00: 0 means kDefaultRapidFeed.
    double feed = 0.0;
    AxisVector target{};  // absolute target of each named axis (program coordinates)
    // Arcs only: the two axes the arc is named in (first, second, in
    // arc_axes), and its centre on those two axes (absolute). G03 turns from
    // the first axis towards the second. Once a TC object was accessed, the
    // arc runs in the active plane instead ([APCI-TC] section 2.2 "Wichtiger
    // Hinweis").
    std::array<double, 2> center{};
    std::uint32_t tag = 0;  // the NC block number; carried into every segment it produces
    ProfileKind kind = ProfileKind::kLine;
    AxisMask axes = 0;  // the axes named; the others keep their position
    std::array<std::uint8_t, 2> arc_axes{0, 1};
};

// Direct commands ([APCI-TC] section 1 names JA and JS as examples; their
// meaning here is design, docs/motion.md). Every direct command discards the
// spooler content and the held profile before it acts.
enum class DirectCode : std::uint16_t {
    kJA = 1,  // jog absolute: the named axes move to `target` at `feed` (0 = rapid)
    kJS = 2,  // jog stop: all axes stop where they are; `axes` must be 0
};
std::string_view direct_code_name(DirectCode c) noexcept;  // "JA", "JS"

struct DirectCommand {
    DirectCode code = DirectCode::kJS;
    AxisMask axes = 0;
    AxisVector target{};
    double feed = 0.0;
};

// SSF command 2001 sent to the axes of a compensation group releases its held
// profile ([APCI-TC] section 1).
inline constexpr std::int32_t kSsfReleaseHeldProfile = 2001;

// What one executed segment was (docs/design.md section 7 JSON "role").
enum class SegmentRole : std::uint8_t {
    kContour = 0,        // a compensated G01/G02/G03 element
    kTransition = 1,     // corner transition between two compensated elements
    kApproach = 2,       // from the position before compensation to the compensated path
    kDeparture = 3,      // from the last compensated element back to the programmed end
    kUncompensated = 4,  // a G01/G02/G03 element without compensation
    kRapid = 5,          // a G00 profile or a JA move
};
std::string_view segment_role_name(SegmentRole r) noexcept;  // "contour", ...

enum class SegmentKind : std::uint8_t { kLine = 0, kArc = 1 };
std::string_view segment_kind_name(SegmentKind k) noexcept;  // "line", "arc"

// An executed segment, in board axes (machine coordinates: after rotation,
// radius and length compensation).
struct Segment {
    std::uint32_t tag = 0;
    SegmentKind kind = SegmentKind::kLine;
    SegmentRole role = SegmentRole::kUncompensated;
    AxisVector start{};
    AxisVector end{};  // where the axes stopped (the planned end unless interrupted)
    // Arcs: plane axes (first, second), centre on them, sense. `center` holds
    // the centre on the plane axes and the start position on all others.
    std::array<std::uint8_t, 2> plane_axes{0, 1};
    AxisVector center{};
    bool ccw = false;
    std::int32_t plane = 0;         // arcs: 17, 18, 19 when in a TC plane's axes, else 0
    double feed = 0.0;              // units/min actually used
    std::uint64_t start_cycle = 0;  // clock value when it started
    std::uint64_t end_cycle = 0;    // clock value when it ended
    bool interrupted = false;       // cut short by a direct command or Reset
    bool traverse = false;          // from a traverse profile (a compensated G00)
    // The tool length compensation in `start` and in `end`, per axis: what the axes carried
    // where the move began (Executor::nominal_length) and its Move::length_end (an interrupted
    // segment's: the part carried where it stopped). The tool centre point is the position
    // less these.
    AxisVector length_start{};
    AxisVector length_end{};
};

// One interpolation cycle's axis positions (machine coordinates), taken after
// the cycle ran: `cycle` is the clock value at the end of that cycle (1 for the first).
struct TraceSample {
    std::uint64_t cycle = 0;
    AxisVector position{};
};

// The answer to every motion call (spool, direct, SSF).
struct MotionResult {
    objif::Status status = objif::Status::kOk;
    // TC errors this call set: the group whose ERROR gets `errors` (Table 4
    // bits) and whose Run clears; `tag` is the block at fault.
    std::int32_t group = 0;
    std::int32_t errors = 0;
    std::uint32_t tag = 0;
    std::string_view message;  // why, in one line (static text); empty when ok
    bool ok() const noexcept { return objif::ok(status); }
};

// A snapshot of the motion part for the host (Board::motion_status()).
struct MotionStatus {
    std::uint64_t now = 0;                // interpolation cycles since power-on
    bool idle = true;                     // nothing moves: queue empty, or held
    bool held = false;                    // the spooler holds after a TC error (ERROR set)
    std::uint32_t fill = 0;               // moves in the queue (the one under way included)
    std::uint32_t capacity = 0;           // the most moves the queue takes
    std::int32_t compensating_group = 0;  // 0: no compensation under way
    bool profile_held = false;            // the compensating group holds a profile (ProfMarked)
    bool tracing = false;                 // per-cycle samples are recorded
    std::uint64_t trace_pending = 0;      // samples waiting to be read
    std::uint64_t trace_lost = 0;         // samples dropped because nobody read them
    std::uint64_t segments_pending = 0;   // executed segments waiting to be read
    std::uint64_t segments_lost = 0;
    AxisVector position{};  // axis positions now (machine coordinates)
};

}  // namespace rwmos::motion
