// SPDX-License-Identifier: MIT
// NC programs shaped the way CAM post-processors write "compensation in control"
// (docs/testing.md, "The gouge oracle"), in our DIN 66025 dialect (docs/nc-programs.md):
//
//   G17 G40 G90 G26 / D n / F .. / G0 Z<safe> / G0 X.. Y.. / G1 Z<level>
//   G41 G1 X.. Y..          a straight lead-in (the approach)
//   G3 X.. Y.. I.. J..      a tangent lead-in arc onto the contour
//   ... the closed contour ...
//   G3 X.. Y.. I.. J..      a tangent lead-out arc
//   G40 G1 X.. Y..          a straight lead-out (the departure)
//   G0 Z<safe> / M30
//
// with coordinates written to 3 or 4 decimals (with or without N numbers, with or without
// modal words left out). Each program comes with its tool list, the tool radius of every block,
// and its DESIGN PART: the material it must leave standing, as the boundary elements the
// program wrote (rounded as written), each tagged with its block and the side the material is
// on (stock_oracle.h). Correct programs leave the part intact; gouge programs cut it by
// construction (a neck, a keyhole, a tongue, features or an island too close, a lead-in across
// the part), each designed gouge at least 2e-3 mm deeper than the path tolerance (1e-4 mm), at
// one cutting level; some shapes the compensation itself refuses (a concave arc smaller than
// the tool) before anything cuts.
//
// Every draw is deterministic in (family, seed) (tests/support/rng.h). A draw whose geometry
// does not fit (a lead that would not clear the walls, an element too short for its corners,
// features that do not fit apart) is drawn again, never written.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "apci/run/path.h"
#include "stock_oracle.h"

namespace apci::test {

enum class CamFamily {
    // Correct programs.
    kLeadLineArcPocket,  // straight + tangent arc leads, G41/G42, inside a pocket
    kLeadLineArcBoss,    // ... outside a boss
    kLeadLinePocket,     // straight leads only (onto a straight edge: the corner trims them)
    kLeadLineBoss,
    kLeadArcPocket,  // arc leads only (G41 alone, the arc the first element; lifted out)
    kLeadArcBoss,
    kRoundedRectangle,  // closed contours, pocket or boss, any lead
    kSlot,
    kCircle,              // as one full circle, two halves or four quarters
    kFilletedPolygon,     // convex polygons with fillets (sharp where the tool trims)
    kIsland,              // a pocket with an island, two stretches
    kRooms,               // a pocket of two rooms joined by a passage wider than the tool
    kKeyhole,             // a boss with a keyhole: a channel wider than the tool into a chamber
    kTongue,              // a pocket with a tongue of material reaching into it
    kUShape,              // a boss with a slot between two prongs
    kStepoverOneStretch,  // a pocket cleared in offset loops, one stretch (LinuxCNC's qpocket)
    kStepoverPerLoop,     // ... one stretch per loop, each with leads
    kZigzag,              // uncompensated zig-zag rows, then the compensated finishing contour
    kCircularInsideOut,   // a circular pocket widened in passes, growing
    kCircularOutsideIn,   // ... the wall first, then smaller passes
    kSeveralFeatures,     // 2 to 4 pockets in a plate or bosses, G40 and tools between them
    kDepthPasses,         // one contour at 2 to 4 Z levels
    // True gouges the compensation runs (the run must warn them).
    kGougeNeck,                // rooms joined by a passage narrower than 2r
    kGougeKeyhole,             // a keyhole whose channel is narrower than 2r
    kGougeTongue,              // a tongue whose tip comes within 2r of the opposite wall
    kGougeBossesClose,         // two bosses closer than 2r
    kGougeIslandClose,         // an island closer than 2r to its pocket's wall
    kGougeLeadCrossesPart,     // a lead-in across a prong of its own part
    kGougeLeadCrossesFeature,  // a lead-in across a boss milled before
    // True gouges the compensation refuses (a concave arc smaller than the tool, an element too
    // short for its corners): the run stops with an error there.
    kRefusedPocketFillet,  // a pocket corner rounded smaller than the tool
    kRefusedBossScallop,   // a concave scallop in a boss's edge smaller than the tool
    kRefusedNotch,         // a notch in a boss narrower than the tool (round or flat bottom)
    kRefusedSlot,          // a slot narrower than the tool, plunged into at its centre
};

struct CamFamilyInfo {
    CamFamily family;
    bool gouge;             // a true gouge by construction
    bool may_refuse;        // the compensation refuses it (before anything cuts)
    std::string_view name;  // "lead.line+arc.pocket", "gouge.neck", ...
};
// Every family, the correct ones first.
std::span<const CamFamilyInfo> cam_families();
const CamFamilyInfo& family_info(CamFamily family);

// One feature of a program (a contour with its leads, a pass, a zig-zag).
struct CamFeature {
    std::string what;  // "pocket: rounded rectangle 40.0 x 25.0, corners 4.0, G41"
    std::uint64_t first_line = 0, last_line = 0;
    int tool = 0;       // D number
    double radius = 0;  // its radius
};

// A gouge the generator built in: the path of `path_line`'s block comes within the tool radius
// of the wall `wall_line` programmed, by `depth` as designed (exact geometry, before rounding).
struct DesignedGouge {
    std::uint64_t path_line = 0;
    std::uint64_t wall_line = 0;
    double depth = 0.0;
};

struct CamProgram {
    CamFamily family{};
    std::uint64_t seed = 0;
    std::string name;       // "gouge.neck#17"
    std::string text;       // the NC program
    std::string tool_list;  // its tool list (wz[n].gueltig 1, .typ 0, .mass_einheit 1, ...)
    std::vector<CamFeature> features;
    DesignPart part;  // what it must leave standing
    bool gouge = false;
    bool may_refuse = false;
    std::vector<DesignedGouge> designed;  // gouge programs: at least one
    // Where the compensation refuses it (the element smaller than the tool, or the one its
    // refusal names): the lines a run's error may name.
    std::vector<std::uint64_t> refused_at;
    // The tool radius in force when each source line runs (index: line, 1-based; [0] unused).
    std::vector<double> radius_by_line;
    // N number -> source line (N numbers are unique where a program has them).
    std::vector<std::pair<std::int64_t, std::uint64_t>> line_of_number;

    // The source line of a block reference (by its N number where it has one); 0 if unknown.
    std::uint64_t line_of(const run::BlockRef& b) const;
    // The tool radius in force at a block.
    double radius_at(const run::BlockRef& b) const;
    // The features, one a line.
    std::string summary() const;
};

// The program of `family` drawn from `seed`.
CamProgram generate_cam_program(CamFamily family, std::uint64_t seed);

}  // namespace apci::test
