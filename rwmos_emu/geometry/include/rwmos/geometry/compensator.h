// SPDX-License-Identifier: MIT
// The streaming tool radius compensator with one element of lookahead ([APCI-TC],
// "1 Einfuhrung": one profile is always held back; when the next one arrives the held
// one is corrected, the transition computed, both spooled and the new one held).
//
// Pure: no I/O, no allocation. The spooler (profile queue, STATUS, JOG, direct commands,
// the third axis) lives in rwmos_emu and calls this class:
//   begin(config, position)  when compensation is activated (STATUS = 1) or after a
//                            JOG/G00 move, to re-approach from the current position;
//   push(element, index, out) for every G01/G02/G03 profile, projected to the plane;
//   finish(out)              on deactivation (STATUS = 0) or SSF 2001: spools the held
//                            element and the departure;
//   discard()                on a direct command or Reset: the held element is dropped.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "rwmos/geometry/corner.h"
#include "rwmos/geometry/shared.h"

namespace rwmos::geom {

// What an emitted segment is part of.
enum class SegmentRole : std::uint8_t {
    kContour,     // the offset of a programmed element (possibly trimmed, possibly empty)
    kTransition,  // outside-corner transition after the element `index`
    kApproach,    // from the position at begin() to the first offset element
    kDeparture,   // from the last offset end to the programmed end point
};

// "contour", "transition", "approach", "departure" (the role names of `apcictl run --json`).
std::string_view role_name(SegmentRole role) noexcept;

// One piece of the tool-centre path in plane coordinates. index is the caller's index of
// the programmed element it belongs to: a transition belongs to the element before the
// corner, the approach to the first element, the departure to the last.
struct Segment {
    Element path;
    SegmentRole role = SegmentRole::kContour;
    std::uint32_t index = 0;
};

// The most segments one push() or finish() emits: approach, held contour, the plane-free
// elements waiting with it, and a transition of up to three elements.
inline constexpr std::size_t kMaxSegmentsPerStep = 1 + 1 + kMaxPlaneFreeElements + 3;

// Fixed-capacity output of one step; the caller keeps one and reuses it (no allocation).
class SegmentBatch {
  public:
    static constexpr std::size_t kCapacity = kMaxSegmentsPerStep;
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    const Segment& operator[](std::size_t i) const noexcept { return items_[i]; }
    const Segment* begin() const noexcept { return items_.data(); }
    const Segment* end() const noexcept { return items_.data() + size_; }
    void clear() noexcept { size_ = 0; }
    // Appends; the compensator never emits more than kCapacity in one step.
    void add(const Element& path, SegmentRole role, std::uint32_t index) noexcept {
        if (size_ < kCapacity) items_[size_++] = Segment{path, role, index};
    }

  private:
    std::array<Segment, kCapacity> items_{};
    std::size_t size_ = 0;
};

// How the compensation reaches the contour ([ISG-PROG], "Tool radius compensation (TRC)",
// selection and deselection methods; docs/compensation.md "Approach and departure"):
// kPerpendicular (G237, the board's own): a line at right angles from the tool position onto
//   the first offset element's start; the first element then runs whole.
// kIndirect (G139, the initial state of NC programs): the first programmed element is the
//   approach: one line from the tool position straight to its compensated end (the point at the
//   radius beside its programmed end, at right angles to it), joined to the next element at the
//   corner as its offset element would be; an arc approaches by LinuxCNC's entry arc (approach.h).
// kDirect (G138, [ISG-PROG]'s direct selection): the first programmed element, a line, is the
//   approach: one line from the tool position straight to the offset start of the element after
//   it (the radius beside its programmed start, at right angles to it), with no corner between
//   (a kink, as [ISG-PROG] says of direct selection); an arc as the first element is
//   KorrError kDirectSelectionOnAnArc ([ISG-PROG] builds approach blocks on lines only). Ended
//   before a second element arrives, it runs to its own offset end, as kIndirect's.
// The departure is the spooler's (it keeps or drops the departure finish() emits).
enum class ApproachMode : std::uint8_t { kPerpendicular, kIndirect, kDirect };

struct CompensatorConfig {
    Side side = Side::kLeft;                                // G41 / G42
    double tool_radius = 0.0;                               // >= 0, interpolation units
    TransitionMode transition = TransitionMode::kCircular;  // G26 / G25
    ApproachMode approach = ApproachMode::kPerpendicular;   // G237 / G139 / G138
};

// The outcome of one step. On failure nothing was emitted and the compensator is exactly
// as before the call.
struct StepResult {
    Reason reason = Reason::kNone;
    ErrorBits errors = 0;     // Table 4 bits of reason; 0 on success
    std::uint32_t index = 0;  // the element at fault: the pushed one, or the held one
                              // for kHeldElementTooShort
    bool ok() const noexcept { return reason == Reason::kNone; }
};

// Validates a configuration: kInvalidToolRadius, kInvalidSetting or kNone.
Reason check_config(const CompensatorConfig& config) noexcept;

class PathCompensator {
  public:
    // Starts compensating from the tool position (plane coordinates). Fails with
    // kAlreadyStarted while running, or on a bad config or position.
    StepResult begin(const CompensatorConfig& config, const Vec2& position) noexcept;

    // Takes the next programmed element. out is cleared, then receives: the approach (on
    // the first plane element; kIndirect: none yet, the first element is held as the approach
    // and emitted with role kApproach), or the finished held element, the plane-free elements
    // that waited with it (zero-length lines at its end), and the corner's transition.
    // The new element is held. A plane-free element (no motion in the plane) waits with
    // the held element, or, before the first plane element, is emitted at once as a
    // zero-length approach at the start position.
    StepResult push(const Element& programmed, std::uint32_t index, SegmentBatch& out) noexcept;

    // Ends compensation: emits the held element to its untrimmed offset end, the
    // plane-free elements that waited with it, and the departure to the programmed end.
    StepResult finish(SegmentBatch& out) noexcept;

    // Drops the held element and ends compensation without output (direct command).
    void discard() noexcept;

    // Changes the outside-corner transition (G25 / G26, the TC CornerMode object) for the
    // corners still to come, the one after the held element included; the running contour
    // goes on. kInvalidSetting (nothing changes) for an undefined mode.
    Reason set_transition(TransitionMode mode) noexcept;

    bool running() const noexcept { return state_ != State::kIdle; }
    // A programmed element is held back (STATUS bit ProfMarked).
    bool holds_element() const noexcept { return state_ == State::kHolding; }
    std::uint32_t held_index() const noexcept { return held_index_; }
    const CompensatorConfig& config() const noexcept { return config_; }

  private:
    enum class State : std::uint8_t { kIdle, kStarted, kHolding };

    StepResult fail(Reason reason, std::uint32_t index, SegmentBatch& out) const noexcept;
    void emit_plane_free(const Vec2& at, SegmentBatch& out) const noexcept;
    // The held element as emitted: its offset path, or the indirect approach to its end.
    Element held_path(const OffsetElement& held) const noexcept;

    CompensatorConfig config_;
    Vec2 position_ = Vec2::Zero();     // tool position at begin()
    OffsetElement held_;               // held offset element, its start final
    Element first_programmed_;         // the indirect approach's programmed element
    Vec2 held_corner_ = Vec2::Zero();  // programmed end of the held element
    Vec2 held_end_tangent_ = Vec2::Zero();
    double held_length_ = 0.0;  // programmed length of the held element
    std::size_t plane_free_count_ = 0;
    std::array<std::uint32_t, kMaxPlaneFreeElements> plane_free_{};
    std::uint32_t held_index_ = 0;
    State state_ = State::kIdle;
    SegmentRole held_role_ = SegmentRole::kContour;  // kApproach: the indirect approach
};

}  // namespace rwmos::geom
