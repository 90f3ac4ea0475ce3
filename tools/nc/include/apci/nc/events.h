// SPDX-License-Identifier: MIT
// What the interpreter hands to the executor: moves in absolute coordinates and the modal
// changes the executor must act on, one event at a time, each with the block and line it came
// from. Coordinates are the programmed contour (tool centre before compensation) in program
// units (mm); compensation itself is the board's job (TC module, DESIGN.md section 3).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <variant>

#include "apci/nc/block.h"
#include "apci/nc/diagnostic.h"

namespace apci::nc {

struct BlockOrigin {
    std::int64_t block = kNoBlockNumber;  // N number, kNoBlockNumber (-1) when the block has none
    std::uint64_t line = 0;               // 1-based source line
};

// G0: rapid move, no feed, never compensated.
struct RapidMove {
    Eigen::Vector3d start;
    Eigen::Vector3d end;
};

// G1: straight line at the feed rate.
struct LineMove {
    Eigen::Vector3d start;
    Eigen::Vector3d end;
    double feed = 0.0;  // mm/min, > 0
};

// G2 (clockwise) / G3 (counter-clockwise), seen looking from the positive axis normal to the
// plane towards the plane (G17: from +Z, G18: from +Y, G19: from +X). The centre's coordinate on
// the normal axis is the start's; an end differing from the start on that axis makes a helix.
// start == end in the plane is a full circle (only programmable with I/J/K).
struct ArcMove {
    Eigen::Vector3d start;
    Eigen::Vector3d end;
    Eigen::Vector3d center;
    bool ccw = false;
    Plane plane = Plane::kXY;
    double feed = 0.0;  // mm/min, > 0
};

// D n: select tool data set n (0: no tool). Sent for every D word, also when n is unchanged.
struct ToolSelect {
    int tool = 0;
};

// G40 / G41 / G42, sent when the side changes.
struct CompensationChange {
    Compensation side = Compensation::kOff;
};

// G25 / G26, sent when the mode changes.
struct CornerModeChange {
    CornerMode mode = CornerMode::kCircular;
};

// G17 / G18 / G19, sent when the plane changes.
struct PlaneChange {
    Plane plane = Plane::kXY;
};

// M30.
struct ProgramEnd {};

using EventData = std::variant<RapidMove, LineMove, ArcMove, ToolSelect, CompensationChange,
                               CornerModeChange, PlaneChange, ProgramEnd>;

struct Event {
    BlockOrigin origin;
    EventData data;
};

// "rapid", "line", "arc", "tool", "compensation", "corner", "plane", "end".
std::string_view event_name(const EventData& data) noexcept;

// The events of one block, in the order the executor must act on them (docs/nc-programs.md):
// tool select, plane, corner mode, compensation, the move, program end.
class EventBatch {
  public:
    static constexpr std::size_t kCapacity = 6;

    void clear() noexcept { size_ = 0; }
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    const Event& operator[](std::size_t i) const noexcept { return events_[i]; }
    const Event* begin() const noexcept { return events_; }
    const Event* end() const noexcept { return events_ + size_; }
    // The interpreter never adds more than kCapacity (one per kind above).
    void push(const BlockOrigin& origin, const EventData& data) noexcept {
        events_[size_].origin = origin;
        events_[size_].data = data;
        ++size_;
    }

  private:
    Event events_[kCapacity];
    std::size_t size_ = 0;
};

}  // namespace apci::nc
