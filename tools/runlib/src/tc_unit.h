// SPDX-License-Identifier: MIT
// The TC module's unit of the executor (bus 1300; docs/apcictl.md "run"): the three
// compensation groups, the tool (D n), the plane (G17..G19), the corner mode (G25/G26) and the
// radius compensation (G40..G42).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/events.h"
#include "apci/run/executor.h"
#include "module_unit.h"
#include "objif/map/object_map.h"

namespace apci::run::exec {

inline constexpr std::int32_t kGroups = objif::map::tc::kGroupCount;
// The least tool radius G41/G42 compensates with without a notice (mm): 1 um, less than any
// cutter's, more than a radius in mm written into a tool list in its 0.1 um unit (radius 5:
// 0.0005 mm).
inline constexpr double kLeastRadius = 1e-3;

class TcUnit final : public ModuleUnit {
  public:
    explicit TcUnit(RunContext& run) noexcept : ModuleUnit(run) {}

    // The TC module's state as the run set it: written by TcUnit alone, read by the executor and
    // the other units through state(). (Its name is the unit's: the board's own is rwmos::TcState.)
    struct State {
        int plane = 17;                 // G17..G19 in force (TcPlane)
        int comp_plane = 17;            // the plane of the compensation under way or last run
        int comp_side = 1;              // its side: +1 left (G41), -1 right (G42)
        bool comp_on = false;           // G41/G42 in force
        bool comp_plane_seen = false;   // a compensation began (its plane is the plot's)
        bool length_always = false;     // the groups' LengthMode 1: the length on every move
        int current_tool = 0;           // D n in force
        double length = 0.0;            // WkzLen of the current tool, as the board has it (mm)
        double radius = 0.0;            // RADIUS of the current tool (mm)
        std::int32_t cutting_edge = 0;  // CuttingEdge of the current tool (srk_lage)
    };

    const State& state() const noexcept { return state_; }

    bool setup();
    bool tool(const BlockRef& at, int index);
    bool plane(const BlockRef& at, nc::Plane p);
    bool corner(const BlockRef& at, nc::CornerMode m);
    bool selection(const BlockRef& at, nc::SelectionMode m);
    bool compensation(const BlockRef& at, nc::Compensation side);
    bool compensation_off(const BlockRef& at);
    // When WkzLen acts (LengthMode): on every move (`always`, as NC programs run, from setup on)
    // or only while a group compensates (under #TRAFO, whose transformation carries the
    // length). The axes stop first: the segments read back so far ran in the old mode.
    bool length_mode(const BlockRef& at, bool always);
    void read_registers();
    // WkzLen read back (the OTC module folded the tool's wear into it at #OTC OFF): the
    // segments read from here on carry the new length. False when it cannot be read (the
    // length stays as it was).
    bool read_length();

  private:
    // Writes value to sub of every group (CornerMode, SelectionMode: the program's modes).
    bool every_group(const BlockRef& at, std::int32_t sub, std::int32_t value,
                     std::string_view what);
    // A notice where G41/G42 compensates with a radius under kLeastRadius (once per tool).
    void notice_small_radius(const BlockRef& at, nc::Compensation side);

    State state_;
    std::vector<int> small_radius_tools_;  // the tools notice_small_radius() named
};

}  // namespace apci::run::exec
