// SPDX-License-Identifier: MIT
// Where a radius-compensated path comes near the contour away from its corners. A control with
// one element of lookahead (the TC module, LinuxCNC) computes each corner from the two elements
// that meet there; where the contour crosses or comes back near itself, the tool path of one
// element can come closer than the tool radius to another element that is not its neighbour,
// and no corner rule sees it. `apcictl run` sees the whole program: this check compares every
// executed compensated segment with every programmed compensated element that is not its
// neighbour, in the plane of compensation, and reports each place where they come closer than
// the tool radius less the path tolerance (docs/compensation.md, "Self-approach"); the element
// before and the one after count too (at their common corner the corner rule keeps the path r
// from them; away from it an arc curling round, or a contour coming back alongside after a
// reversal, can come closer), with twice the tolerance (a tangent join may move a start by it).
// The first and the last element of each compensated stretch are its approach and departure:
// paths must not come near the elements between, not near those two.
//
// Cost: a uniform grid of the programmed elements and of the executed segments, each kept once
// (an element programmed again with the same geometry, as depth passes repeat a contour, is
// checked once); at most kMaxElements of each per plane (beyond them the check says so).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "apci/run/path.h"

namespace apci::run {

namespace detail {
struct Shape;
}

struct SelfApproachFinding {
    BlockRef path_block;     // the block whose compensated path comes near
    BlockRef contour_block;  // the programmed element it comes near (not a neighbour)
    double distance = 0.0;   // the least distance found, mm
    double radius = 0.0;     // the tool radius, mm
    Point where = Point::Zero();  // the point of the path, program coordinates
};
// "the tool path of N40 comes within 1.2000 mm of the contour at N90 (tool radius 2.0000 mm):
// ...". The message of the run's warning (or error).
std::string describe(const SelfApproachFinding& f);

class SelfApproachCheck {
  public:
    static constexpr std::size_t kMaxElements = std::size_t{1} << 18;
    // Each pair of blocks is reported once; at most this many pairs.
    static constexpr std::size_t kMaxFindings = 1000;
    // How much closer than the tool radius a path may come: the compensation's path tolerance.
    static constexpr double kTolerance = 1e-4;

    SelfApproachCheck();
    ~SelfApproachCheck();
    SelfApproachCheck(const SelfApproachCheck&) = delete;
    SelfApproachCheck& operator=(const SelfApproachCheck&) = delete;

    // A compensated stretch begins (G41/G42, or the first move after a rapid under G41/G42):
    // tool radius r (mm) in plane 17, 18 or 19.
    void begin(double r, int plane);
    // It ends (G40, a rapid move, the end of the program); findings against elements that were
    // not its last are appended to `out`.
    void end(std::vector<SelfApproachFinding>& out);
    bool active() const noexcept { return active_; }
    // A line or arc spooled in the stretch, in program order; findings (a path executed
    // before that comes near it) are appended to `out`.
    void programmed(const PathSegment& s, std::vector<SelfApproachFinding>& out);
    // A segment the board executed (every one, in order); findings are appended to `out`.
    void executed(const PathSegment& s, std::vector<SelfApproachFinding>& out);
    // True when more elements than kMaxElements came: the rest were not checked.
    bool truncated() const noexcept;

  private:
    struct Grid;
    using Shape = detail::Shape;
    struct Pending {
        BlockRef block;
        std::uint64_t index = 0;    // of the element, counted over the whole program
        std::uint64_t stretch = 0;  // of its stretch
        double r = 0.0;
        int plane = 17;
    };
    Grid& grid(int plane);
    // True with `f` filled when path comes closer than threshold to contour (each pair of
    // blocks once).
    bool report(const Shape& path, const BlockRef& path_block, double r, int plane,
                const Shape& contour, const BlockRef& contour_block, double threshold,
                SelfApproachFinding& f);

    std::unique_ptr<Grid> grids_[3];
    std::vector<Pending> pending_;  // programmed compensated elements, from pending_head_
    std::size_t pending_head_ = 0;  // the first not yet executed
    std::vector<std::array<std::uint64_t, 4>> reported_;  // (path, contour) block pairs, once
    static constexpr std::uint32_t kNone = ~std::uint32_t{0};
    // Findings against the stretch's latest element, held until it is known not to be the last.
    std::vector<std::pair<SelfApproachFinding, std::uint32_t>> held_;
    std::uint32_t latest_ = kNone;  // grid id of the stretch's latest element (new geometry)
    bool first_in_stretch_ = false;
    bool active_ = false;
    double r_ = 0.0;
    int plane_ = 17;
    std::uint64_t stretch_ = 0;
    std::uint64_t next_index_ = 0;
};

}  // namespace apci::run
