// SPDX-License-Identifier: MIT
// Tools of the 3D compensation ([TNC-3D], "Werkzeuge für die 3D-Werkzeugkorrektur"): the
// shape by R and R2, the delta values DL, DR, DR2 and their sum, the effective tool the
// control positions, and the oversize rule of M107.
#pragma once

#include <cstdint>

#include "rwmos/comp3d/refusal.h"

namespace rwmos::comp3d {

// Radius R and corner radius R2 as in the tool table (mm).
struct ToolDimensions {
    double r = 0.0;
    double r2 = 0.0;
};

// [TNC-3D]: "Schaftfräser: R2 = 0, Torusfräser: R2 > 0, Kugelfräser: R2 = R".
enum class ToolShape : std::uint8_t { kEndMill, kToroidal, kBall };

// Finite, 0 <= R, 0 <= R2 <= R (+kShapeTolerance), at most kMaxCoordinate.
Refusal check_tool(const ToolDimensions& tool) noexcept;
// The shape of a tool that passed check_tool(): R2 within kShapeTolerance of 0 is an end
// mill, of R a ball mill (an R = 0 tool is an end mill), anything between toroidal.
ToolShape tool_shape(const ToolDimensions& tool) noexcept;

// Delta values (mm): DL on the length, DR on the radius, DR2 on the corner radius.
struct Deltas {
    double dl = 0.0;
    double dr = 0.0;
    double dr2 = 0.0;
};
constexpr Deltas operator+(const Deltas& a, const Deltas& b) noexcept {
    return {a.dl + b.dl, a.dr + b.dr, a.dr2 + b.dr2};
}

// Where delta values come from ([TNC-3D]: "die Summe der Deltawerte aus der
// Werkzeugverwaltung, dem Werkzeugaufruf und den Korrekturtabellen").
struct DeltaSources {
    Deltas tool_table;        // wz[i].dl, .dr, .dr2
    Deltas tool_call;         // TOOL CALL n Z DL.. DR.. DR2..
    Deltas correction_table;  // the object-addressable correction table
};
constexpr Deltas sum_deltas(const DeltaSources& s) noexcept {
    return s.tool_table + s.tool_call + s.correction_table;
}

// Each delta finite and at most kMaxCoordinate in size.
Refusal check_deltas(const Deltas& d) noexcept;

// The tool the control positions: R + DR, R2 + DR2 (the length L + DL acts along T, see
// compensation.h).
constexpr ToolDimensions effective_tool(const ToolDimensions& tool, const Deltas& d) noexcept {
    return {tool.r + d.dr, tool.r2 + d.dr2};
}
// The effective tool must exist: R + DR >= 0, R2 + DR2 >= 0, R2 + DR2 <= R + DR (each within
// kShapeTolerance). Expects check_tool(tool) and check_deltas(d) to have passed.
Refusal check_effective_tool(const ToolDimensions& tool, const Deltas& d) noexcept;

// A summed delta above kOversizeTolerance: the tool is larger than the tool table says.
bool has_positive_oversize(const Deltas& sum) noexcept;
// [TNC-3D]: loading a tool with positive delta values is an error unless M107 allows it.
Refusal check_oversize(const Deltas& sum, bool m107_active) noexcept;

// Everything a tool must pass when it is loaded: the table tool, the deltas, the effective
// tool and the oversize rule, in that order; the first refusal.
Refusal check_tool_load(const ToolDimensions& tool, const Deltas& sum, bool m107_active) noexcept;

}  // namespace rwmos::comp3d
