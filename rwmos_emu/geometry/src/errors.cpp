// SPDX-License-Identifier: MIT
#include "rwmos/geometry/errors.h"

#include <array>

namespace rwmos::geom {
namespace {

struct ReasonRow {
    Reason reason;
    ErrorBits bits;
    std::string_view name;
    std::string_view message;
};

constexpr ErrorBits kInit = bits(ErrorBit::kInitError);
constexpr ErrorBits kKorr = bits(ErrorBit::kKorrError);
constexpr ErrorBits kCalc = bits(ErrorBit::kCalcError);
constexpr ErrorBits kCenter = bits(ErrorBit::kCenterError);

// The one table; the static_assert keeps it in step with the enum.
constexpr std::array kReasonTable{
    ReasonRow{Reason::kNone, 0, "None", "no error"},
    ReasonRow{Reason::kNotStarted, kInit, "NotStarted",
              "compensation not started: begin() must come before push() and finish()"},
    ReasonRow{Reason::kAlreadyStarted, kInit, "AlreadyStarted",
              "compensation already running: finish() or discard() before begin()"},
    ReasonRow{Reason::kInvalidToolRadius, kInit, "InvalidToolRadius",
              "tool radius must be finite, >= 0 and at most 1e5"},
    ReasonRow{Reason::kInvalidSetting, kInit, "InvalidSetting",
              "side or transition mode is not one of the defined values"},
    ReasonRow{Reason::kInvalidCoordinate, kCalc, "InvalidCoordinate",
              "a coordinate is not finite or lies beyond +-1e5"},
    ReasonRow{Reason::kInvalidElementKind, kCalc, "InvalidElementKind",
              "element is neither a line nor an arc"},
    ReasonRow{Reason::kOffsetRadiusNotPositive, kCalc, "OffsetRadiusNotPositive",
              "arc radius is smaller than the tool radius on the concave side: the tool would cut "
              "into the "
              "arc (use a tool no larger than the arc's radius)"},
    ReasonRow{Reason::kArcCentreOnEndPoint, kCenter, "ArcCentreOnEndPoint",
              "arc centre coincides with the arc's start or end point"},
    ReasonRow{
        Reason::kArcRadiiDiffer, kCenter, "ArcRadiiDiffer",
        "arc start and end radius differ by more than 0.003: the end point is not on the circle "
        "through the start (check the centre words and the end point)"},
    ReasonRow{Reason::kDiscontinuous, kKorr, "Discontinuous",
              "element does not start where the previous element ends"},
    ReasonRow{
        Reason::kHeldElementTooShort, kKorr, "HeldElementTooShort",
        "element is too short for the corner at its end: its offset would reverse (lengthen it, "
        "join it into its neighbour, or use a smaller tool)"},
    ReasonRow{
        Reason::kNextElementTooShort, kKorr, "NextElementTooShort",
        "element is too short for the corner at its start: its offset would reverse (lengthen "
        "it, join it into its neighbour, or use a smaller tool)"},
    ReasonRow{
        Reason::kNoCornerSolution, kKorr, "NoCornerSolution",
        "offset elements do not meet at this inside corner: the tool does not fit into it (use a "
        "smaller tool)"},
    ReasonRow{Reason::kTooManyPlaneFreeElements, kKorr, "TooManyPlaneFreeElements",
              "too many consecutive elements without motion in the compensation plane"},
    ReasonRow{Reason::kApproachArcNoSolution, kKorr, "ApproachArcNoSolution",
              "the approach (the first move of the compensation) is an arc, and no arc leads from "
              "the tool to its compensated end (start the approach elsewhere, or with a G01)"},
    ReasonRow{Reason::kDirectSelectionOnAnArc, kKorr, "DirectSelectionOnAnArc",
              "direct selection (G138): the selection block is an arc, and approach blocks are "
              "built on lines only (select with a G01, or with G139)"},
};
static_assert(kReasonTable.size() == kReasonCount, "reason table and enum out of step");

constexpr bool rows_in_enum_order() {
    for (std::size_t i = 0; i < kReasonTable.size(); ++i)
        if (static_cast<std::size_t>(kReasonTable[i].reason) != i) return false;
    return true;
}
static_assert(rows_in_enum_order(), "reason table rows must follow the enum order");

const ReasonRow* find_row(Reason r) noexcept {
    const auto i = static_cast<std::size_t>(r);
    return i < kReasonTable.size() ? &kReasonTable[i] : nullptr;
}

}  // namespace

std::string_view error_bit_name(ErrorBit b) noexcept {
    switch (b) {
        case ErrorBit::kInitError:
            return "InitError";
        case ErrorBit::kKorrError:
            return "KorrError";
        case ErrorBit::kCalcError:
            return "CalcError";
        case ErrorBit::kPlaneError:
            return "PlaneError";
        case ErrorBit::kCenterError:
            return "CenterError";
    }
    return "Unknown";
}

ErrorBits reason_bits(Reason r) noexcept {
    const auto* row = find_row(r);
    return row ? row->bits : kCalc;
}

std::string_view reason_name(Reason r) noexcept {
    const auto* row = find_row(r);
    return row ? row->name : std::string_view{"Unknown"};
}

std::string_view reason_message(Reason r) noexcept {
    const auto* row = find_row(r);
    return row ? row->message : std::string_view{"unknown reason"};
}

}  // namespace rwmos::geom
