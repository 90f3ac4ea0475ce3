// SPDX-License-Identifier: MIT
// `apcictl run --plc FILE`: a scripted PLC for the OTC control units ([ISG-OTC],
// section 2.7) and the temperature compensation's setting data ([SIN-TEMP], SD 42960: "von der
// PLC aus vom Anwender beschrieben"), so that a program runs end to end without a real PLC.
// One write a line:
//
//   # when        unit                        value
//   cycle 0       otc_radius_offset.enable    1
//   block 60      otc_radius_offset.command   20000
//   cycle 15000   otc_offset[2].command       -500
//   cycle 0       tool_temp_comp_on           1
//   cycle 0       temp_comp_type[2]           4
//   cycle 8000    tool_temp_comp[2]           0.015
//   cycle 0       tool_holder                 1
//
// `cycle N`: when the board's clock, counted from the start of the run, reaches N (the executor
// stops the clock there; entries past the program's end are written after it, the clock running
// on to them). `block N`: when the program reaches block N, after every move before it has run
// (each time the block is reached, also in a loop). Units: `otc_radius_offset` (the channel
// unit) and `otc_offset[i]` (the axis unit of channel axis i: 0 X, 1 Y, 2 Z through the TC
// Axis-Nr, 3..7 the board axis of that number), field `command` (0.1 um, DINT) or `enable`
// (0/1, TRUE/FALSE); `tool_temp_comp[i]` (SD 42960 component i 0..2, mm, within the object's
// +-1e5), `tool_temp_comp_on` (MD 20390, 0/1), `temp_comp_type[i]` (MD 32750 of channel
// axis i, 0..255), and the design objects `tool_holder` (0/1: the vector turns with the head),
// `tool_holder_axis_b` (board axis 0..7), `tool_holder_axis_c` (-1..7, -1 none) and
// `temp_ramp_velocity` (mm/s, 1e-6..1e5) of bus 1320. `#` starts a comment. docs/apcictl.md
// ("run --plc") is the spec.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "apci/nc/diagnostic.h"
#include "apci/nc/source.h"

namespace apci::run {

// The latest cycle a `cycle N` entry may name: 10^9, 11.6 days of board time at 1 ms. After the
// program the clock runs on to the last entry; a larger N would keep a run going for hours (10^18
// ran on without end). The bound of `apcictl step`, for the same reason.
inline constexpr std::uint64_t kMaxPlcCycle = 1'000'000'000;

// What `--plc FILE` may hold: it is read whole before the run, at most kMaxPlcScriptBytes
// (16 MiB: at most about 760,000 writes, 22 bytes each at the shortest), each line at most
// kMaxPlcLineLength characters without its line end (as an NC program's line,
// apci::nc::LineSource). /dev/zero was read to 1.2 GB, then std::bad_alloc.
inline constexpr std::size_t kMaxPlcScriptBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxPlcLineLength = nc::LineSource::kMaxLineLength;

struct PlcWrite {
    enum class When : std::uint8_t { kCycle, kBlock };
    // OTC control units (bus 1330) and the temperature compensation's objects (bus 1320).
    enum class Unit : std::uint8_t {
        kOtcRadiusOffset,   // otc_radius_offset.<field>
        kOtcOffset,         // otc_offset[index].<field>
        kToolTempComp,      // tool_temp_comp[index]: SD 42960
        kToolTempCompOn,    // tool_temp_comp_on: MD 20390
        kTempCompType,      // temp_comp_type[index]: MD 32750
        kToolHolder,        // tool_holder: ToolHolder (Index 4)
        kToolHolderAxisB,   // tool_holder_axis_b: HeadAxisB (Index 5)
        kToolHolderAxisC,   // tool_holder_axis_c: HeadAxisC (Index 6)
        kTempRampVelocity,  // temp_ramp_velocity: RampVelocity (Index 7)
    };
    enum class Field : std::uint8_t { kCommand, kEnable };  // the OTC units' field
    When when = When::kCycle;
    std::uint64_t at = 0;  // cycle count from the run's start, or the block's N number
    Unit unit = Unit::kOtcRadiusOffset;
    int index = 0;  // kOtcOffset, kTempCompType: channel axis 0..7; kToolTempComp: 0..2
    Field field = Field::kCommand;
    double value = 0.0;  // a whole number (int32 object) but for kToolTempComp, kTempRampVelocity
    std::uint64_t line = 0;  // in the script

    bool otc() const noexcept { return unit == Unit::kOtcRadiusOffset || unit == Unit::kOtcOffset; }
    // A 0/1 unit (TRUE and FALSE accepted).
    bool flag() const noexcept {
        return (otc() && field == Field::kEnable) || unit == Unit::kToolTempCompOn ||
               unit == Unit::kToolHolder;
    }
};

// "otc_radius_offset.command", "otc_offset[2].enable", "tool_temp_comp[2]", ...
std::string plc_unit_name(const PlcWrite& w);

class PlcScript {
  public:
    // The cycle writes in order of their cycle (ties in file order), then the block writes.
    const std::vector<PlcWrite>& cycle_writes() const noexcept { return cycle_; }
    const std::vector<PlcWrite>& block_writes() const noexcept { return block_; }
    const std::string& file() const noexcept { return file_; }

  private:
    friend nc::Result<PlcScript> parse_plc_script(std::string_view text, std::string_view file);
    std::vector<PlcWrite> cycle_;
    std::vector<PlcWrite> block_;
    std::string file_;
};

// Errors name file, line and column and what was expected.
nc::Result<PlcScript> parse_plc_script(std::string_view text, std::string_view file);
nc::Result<PlcScript> load_plc_script(const std::string& path);

}  // namespace apci::run
