// SPDX-License-Identifier: MIT
// One parsed DIN 66025 block (one line): which words it has, their values and columns.
// Fixed size, no heap: the parser refills the same Block for every line.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "geometry/plane.h"
#include "objif/map/limits.h"

namespace apci::nc {

// Modal groups of the DIN 66025 subset; the enumerator values are the G numbers.
enum class Motion : std::uint8_t { kRapid = 0, kLine = 1, kArcCw = 2, kArcCcw = 3 };
// The plane (G17 G18 G19) is the one board and host share: its values are the G numbers.
using Plane = geom::Plane;
enum class DistanceMode : std::uint8_t { kAbsolute = 90, kIncremental = 91 };
enum class Compensation : std::uint8_t { kOff = 40, kLeft = 41, kRight = 42 };
// Outside corners under radius compensation ([ISG-OTC-EN], wr_quad_disc.nc: G25 "linearer
// Übergangssatz", G26 "zirkularer Übergangssatz").
enum class CornerMode : std::uint8_t { kLinear = 25, kCircular = 26 };
// How the radius compensation reaches and leaves the contour ([ISG-PROG], selection and
// deselection methods): G139 indirect (the initial state: the selection block is the approach,
// the G40 block the departure), G237 perpendicular (right-angle moves onto and off the contour).
enum class SelectionMode : std::uint8_t { kDirect = 138, kIndirect = 139, kPerpendicular = 237 };
// Input units ([ISG-PROG]: G70 inch, G71 metric, the initial state): lengths and feeds of the
// program's words. Events are in mm whatever the program's units.
enum class Units : std::uint8_t { kInch = 70, kMetric = 71 };
inline constexpr double kMillimetresPerInch = 25.4;
// The board's coordinate limit (objif/map/limits.h, docs/motion.md), in mm: end points
// beyond it, and tool sizes beyond it, are refused by the front end by name.
inline constexpr double kBoardCoordinateLimit = objif::map::kMaxCoordinate;

constexpr int g_number(Motion m) noexcept {
    return static_cast<int>(m);
}
constexpr int g_number(Plane p) noexcept {
    return static_cast<int>(p);
}
constexpr int g_number(DistanceMode d) noexcept {
    return static_cast<int>(d);
}
constexpr int g_number(Compensation c) noexcept {
    return static_cast<int>(c);
}
constexpr int g_number(CornerMode c) noexcept {
    return static_cast<int>(c);
}
constexpr int g_number(SelectionMode m) noexcept {
    return static_cast<int>(m);
}
constexpr int g_number(Units u) noexcept {
    return static_cast<int>(u);
}

// A word of the block: its value and the 1-based column of its address letter; column 0 means
// the block does not have the word.
template <typename T>
struct Word {
    T value{};
    std::uint32_t column = 0;
    constexpr bool present() const noexcept { return column != 0; }
};

inline constexpr int kMaxToolNumber = 1023;  // D and wz[i] (TC module WKZINDEX 0..1023)
// The largest N number, G code or M code a word may carry (13 digits); one beyond is an error
// that shows it as written.
inline constexpr std::uint64_t kMaxWordNumber = 9'999'999'999'999;

// ISG online tool compensation ([ISG-OTC] section 2.1): the processing types and
// modes #OTC names. The values are the OTC module's object values (bus 1330).
enum class OtcType : std::uint8_t { kRadius = 0, kLength = 1, kToolDir = 2, kSurfNormDir = 3 };
enum class OtcMode : std::uint8_t { kCont = 0, kDisc = 1, kAuto = 2 };
std::string_view otc_type_name(OtcType t) noexcept;  // "RADIUS", ...
std::string_view otc_mode_name(OtcMode m) noexcept;  // "CONT", ...
// WEAR_CONST=.. (the programmed constant) / WEAR_CONST_TOOL (the tool's) / neither.
enum class WearConstChoice : std::uint8_t { kUnchanged, kProgrammed, kTool };

struct Block {
    std::uint64_t line = 0;              // 1-based source line
    Word<std::int64_t> number;           // N
    Word<Motion> motion;                 // G0 G1 G2 G3
    Word<Plane> plane;                   // G17 G18 G19
    Word<DistanceMode> distance;         // G90 G91
    Word<Compensation> compensation;     // G40 G41 G42
    Word<CornerMode> corner;             // G25 G26
    Word<SelectionMode> selection;       // G139 G237
    Word<Units> units;                   // G70 G71
    std::array<Word<double>, 3> axis;    // X Y Z, program units (mm, inches under G70)
    Word<double> b_axis;                 // B, degrees: the B head's tilt (docs/design.md section 8)
    std::array<Word<double>, 3> center;  // I J K, incremental from the arc start
    Word<double> radius;                 // R (negative: the larger arc)
    Word<double> feed;                   // F, mm/min (inch/min under G70), > 0
    Word<int> tool;                      // D, 0..kMaxToolNumber (0: no tool)
    Word<bool> end_of_program;           // M30
    // CDON (true) / CDOF (false): whether the compensated elements from this block on are walls
    // of the part for `apcictl run`'s gouge check (docs/compensation.md, "What is a wall").
    Word<bool> collision;

    // Forgets every word (cheaper than assigning Block{}: only the columns say what is present).
    void clear(std::uint64_t line_number) noexcept {
        line = line_number;
        number.column = motion.column = plane.column = distance.column = 0;
        compensation.column = corner.column = units.column = radius.column = feed.column = 0;
        selection.column = 0;
        tool.column = end_of_program.column = b_axis.column = collision.column = 0;
        for (auto& w : axis) w.column = 0;
        for (auto& w : center) w.column = 0;
    }

    bool has_axis_word() const noexcept {
        return axis[0].present() || axis[1].present() || axis[2].present();
    }
    bool has_center_word() const noexcept {
        return center[0].present() || center[1].present() || center[2].present();
    }
    // N number, or kNoBlockNumber (-1) when the block has none.
    std::int64_t block_number() const noexcept { return number.present() ? number.value : -1; }
};

}  // namespace apci::nc
