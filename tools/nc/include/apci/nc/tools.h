// SPDX-License-Identifier: MIT
// The tool list file in the form of [ISG-OTC] (section 2.6 "Spezielle Einstellungen in
// den Werkzeugdaten"): one "wz[i].field value [comment]" a line, '#' comments, blank lines.
// Raw values are kept as written, in the units of [ISG-OTC] section 2.6; accessors convert to mm and degrees.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"

namespace apci::nc {

// wz[i].typ, P-TOOL-00001 ([ISG-OTC] section 3.2).
enum class ToolType : std::int32_t { kMilling = 0, kTurning = 1, kGrinding = 2, kWire = 3 };

// wz[i].ax_ersatz[k]: k = 0..7 (the board has 8 axes).
inline constexpr std::size_t kAxisOffsetCount = 8;

struct ToolData {
    int index = 0;  // i of wz[i], 1..kMaxToolNumber

    // Raw values as in the file; unset data is 0 ([ISG-OTC] section 2.6, "Hinweis").
    std::int32_t gueltig = 0;                          // 1: the data set is valid
    std::int32_t typ = 0;                              // ToolType
    std::int32_t mass_einheit = 0;                     // 0: lengths in 0.1 um, 1: lengths in mm
    double laenge = 0.0;                               // tool length, length unit
    double radius = 0.0;                               // tool radius, length unit
    std::array<double, kAxisOffsetCount> ax_ersatz{};  // per-axis offsets, length unit
    double grinding_wear_const = 0.0;                  // P-TOOL-00030, always 0.1 um/m
    double grinding_max_infeed = 0.0;                  // P-TOOL-00031, always 0.1 um
    double grinding_disc_tilt_angle = 0.0;             // P-TOOL-00138, always 0.0001 degree
    // 3D compensation ([TNC-3D]: R2, DL, DR, DR2), length unit like radius.
    double r2 = 0.0;
    double dl = 0.0;
    double dr = 0.0;
    double dr2 = 0.0;
    // The wear the CNC reported at tool change ([ISG-OTC] section 2.9: wear_radius, the total of
    // discrete and continuous; wear_radius_cont, the continuous part), length unit, added up over
    // the runs that changed the tool out. Already folded into radius and laenge.
    double wear_radius = 0.0;
    double wear_radius_cont = 0.0;
    // The number of teeth (cutting edges) of a milling tool: the TNC tool table's CUT, for feeds
    // per tooth (FZ, [TNC-3D] "Gerade LN"). 0: not given.
    std::int32_t cut = 0;
    // P-TOOL-00002 srk_lage: the cutting edge position 1..9 of a turning tool (typ 1) in the
    // plane of its compensation; 0 (and 9): the nose centre is the controlled point.
    std::int32_t srk_lage = 0;

    bool valid() const noexcept { return gueltig == 1; }
    ToolType type() const noexcept { return static_cast<ToolType>(typ); }
    // mm per unit of the length fields: 0.0001 with mass_einheit 0 (0.1 um), 1 with 1 (mm).
    double length_unit_mm() const noexcept { return mass_einheit == 0 ? 1e-4 : 1.0; }

    double length_mm() const noexcept { return laenge * length_unit_mm(); }
    double radius_mm() const noexcept { return radius * length_unit_mm(); }
    double axis_offset_mm(std::size_t k) const noexcept {
        return k < kAxisOffsetCount ? ax_ersatz[k] * length_unit_mm() : 0.0;
    }
    double r2_mm() const noexcept { return r2 * length_unit_mm(); }
    double dl_mm() const noexcept { return dl * length_unit_mm(); }
    double dr_mm() const noexcept { return dr * length_unit_mm(); }
    double dr2_mm() const noexcept { return dr2 * length_unit_mm(); }
    // 0.1 um/m -> mm per m of path.
    double wear_const_mm_per_m() const noexcept { return grinding_wear_const * 1e-4; }
    double wear_radius_mm() const noexcept { return wear_radius * length_unit_mm(); }
    double wear_radius_cont_mm() const noexcept { return wear_radius_cont * length_unit_mm(); }
    // Setters in mm, stored in the tool's length unit (the tool management folding the wear).
    void set_radius_mm(double mm) noexcept { radius = mm / length_unit_mm(); }
    void set_length_mm(double mm) noexcept { laenge = mm / length_unit_mm(); }
    void set_wear_radius_mm(double mm) noexcept { wear_radius = mm / length_unit_mm(); }
    void set_wear_radius_cont_mm(double mm) noexcept { wear_radius_cont = mm / length_unit_mm(); }
    // 0.1 um -> mm.
    double max_infeed_mm() const noexcept { return grinding_max_infeed * 1e-4; }
    // 0.0001 degree -> degree.
    double disc_tilt_angle_deg() const noexcept { return grinding_disc_tilt_angle * 1e-4; }
};

class ToolTable {
  public:
    // The tool wz[index], or nullptr when no line of the file names it.
    const ToolData* find(int index) const noexcept;
    ToolData* find_mutable(int index) noexcept;
    // Defined tools, ascending by index.
    const std::vector<ToolData>& tools() const noexcept { return tools_; }
    std::size_t size() const noexcept { return tools_.size(); }

    // Creates wz[index] (all zero) if absent; index must be 1..kMaxToolNumber.
    ToolData& define(int index);

  private:
    std::vector<ToolData> tools_;
};

// Parses a tool list. Errors name file, line and column: unknown field, bad index, missing or
// malformed value, value out of range, a field set twice for one tool.
Result<ToolTable> parse_tool_table(std::string_view text, std::string_view file);
// Reads and parses a tool list file (line by line, as the NC programs).
Result<ToolTable> load_tool_table(const std::string& path);
// The table in the same form ("wz[1].radius 300000"), every field a tool has that is not 0
// (gueltig, typ and mass_einheit always), values with at most 6 decimals: parse_tool_table()
// reads it back to the same table (tested).
std::string format_tool_table(const ToolTable& table);

}  // namespace apci::nc
