// SPDX-License-Identifier: MIT
// Error bits of the TC module's ERROR object ([APCI-TC], "Tabelle 4: Fehlerstatuswort
// Error des TC-Moduls") and the reasons the geometry gives for them. Each reason maps to
// exactly one bit through one table (errors.cpp) and carries one line for the user.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace rwmos::geom {

// Bit values exactly as in Table 4. PlaneError is set by the spooler (operation in the
// wrong plane); InitError by the spooler's object hooks and by a bad begin().
enum class ErrorBit : std::uint32_t {
    kInitError = 0x01,    // initialisation error
    kKorrError = 0x02,    // radius compensation not possible
    kCalcError = 0x04,    // calculation error: operation not allowed or not executable
    kPlaneError = 0x08,   // operation in the wrong main plane
    kCenterError = 0x10,  // arc centre wrong: start and end radius differ
};

// A set of ErrorBit values as the ERROR object holds them.
using ErrorBits = std::uint32_t;

constexpr ErrorBits bits(ErrorBit b) noexcept {
    return static_cast<ErrorBits>(b);
}
constexpr bool has(ErrorBits set, ErrorBit b) noexcept {
    return (set & bits(b)) != 0;
}

// "KorrError" etc.; "Unknown" for a value that is not one bit of Table 4.
std::string_view error_bit_name(ErrorBit b) noexcept;

// Why a geometry step failed. kNone means it did not.
enum class Reason : std::uint8_t {
    kNone = 0,
    // InitError: configuration and call order.
    kNotStarted,         // push/finish before begin (or after finish)
    kAlreadyStarted,     // begin while compensating: finish or discard first
    kInvalidToolRadius,  // tool radius negative, not finite or beyond kMaxCoordinate
    kInvalidSetting,     // side or transition mode not one of the defined values
    // CalcError: input that cannot be computed with.
    kInvalidCoordinate,        // a coordinate is not finite or beyond kMaxCoordinate
    kInvalidElementKind,       // an element that is neither a line nor an arc
    kOffsetRadiusNotPositive,  // arc radius < tool radius on the concave side (beyond tolerance)
    // CenterError: the arc centre is wrong.
    kArcCentreOnEndPoint,  // the centre coincides with the start or end point
    kArcRadiiDiffer,       // start and end radius differ by more than kCenterRadiusTolerance
    // KorrError: the compensated path does not exist.
    kDiscontinuous,             // the element does not start where the held one ends
    kHeldElementTooShort,       // the corner would reverse the held element
    kNextElementTooShort,       // the corner would consume more than the whole new element
    kNoCornerSolution,          // the offset elements do not meet at an inside corner
    kTooManyPlaneFreeElements,  // more than kMaxPlaneFreeElements without plane motion
    kApproachArcNoSolution,     // indirect approach: no arc leads from the tool to the arc's offset
    kDirectSelectionOnAnArc,    // direct selection (G138): the selection block is an arc
};

inline constexpr std::size_t kReasonCount = 17;

ErrorBits reason_bits(Reason r) noexcept;            // 0 for kNone
std::string_view reason_name(Reason r) noexcept;     // "HeldElementTooShort"
std::string_view reason_message(Reason r) noexcept;  // one line of English

}  // namespace rwmos::geom
