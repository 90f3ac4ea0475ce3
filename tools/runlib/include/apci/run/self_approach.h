// SPDX-License-Identifier: MIT
// Where a radius-compensated path cuts into what the program leaves standing. A control with
// one element of lookahead (the TC module, LinuxCNC) computes each corner from the two elements
// that meet there; where the contour crosses or comes back near itself, the tool path of one
// element can come closer than the tool radius to another element that is not its neighbour,
// and no corner rule sees it. `apcictl run` sees the whole program: this check compares every
// executed compensated segment with the programmed compensated elements that are walls of the
// part (wall_model.h: the closed contours, not their leads, nor the passes a larger pass clears,
// nor what the program marks with CDOF), in the plane of compensation, and reports each place
// where they come closer than the tool radius less the path tolerance (docs/compensation.md,
// "Self-approach"); the element before and the one after count too (at their common corner the
// corner rule keeps the path r from them; away from it an arc curling round, or a contour
// coming back alongside after a reversal, can come closer), with twice the tolerance (a tangent
// join may move a start by it). An approach is held to its own stretch's walls but those its
// start already stands near and those at its entry point, where only a crossing counts. Of an
// open contour the first element is its approach, and the last is its departure only where no
// move in the plane departs from it (the stretch is left by a lift under G41/G42, or the program
// ends). A pair waits until the stretches of both its elements ended (the wall model decides
// then); the distance reported is the least distance between the path block's segments and the
// element (within 1e-9 mm), not the first point found closer than the threshold.
//
// Cost: a uniform grid of the programmed elements and of the executed segments, each kept once
// (an element programmed again with the same geometry, as depth passes repeat a contour, is
// checked once). A pair that is proved apart by one side of the path or by exact line and arc
// distances is not searched, nor one whose element the wall model already places as no wall.
// Memory is bounded: per plane, each executed segment is compared with at least the last
// `window` distinct programmed elements and each element with the paths of at least as many,
// fewer where they are long (at most kEntryBudget grid entries); at most twice as many are kept,
// and where some were let go the check says so. A call proved to give nothing out (its stretch
// apart from every other, its own pairs clear) is held back and worked only when a later call
// may give something out (Schedule): most of a CAM program's calls are never worked.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "apci/run/path.h"

namespace apci::run {

namespace detail {
struct Shape;
struct StoredShape;
class WallModel;
enum class WallRole : std::uint8_t;
}

// What comes near what: a stretch's path near its own contour, a path near another stretch's
// (another feature), a lead-in (the approach) or a lead-out (the departure) near the part.
enum class SelfApproachKind : std::uint8_t { kContour, kFeatures, kLeadIn, kLeadOut };

struct SelfApproachFinding {
    BlockRef path_block;     // the block whose compensated path comes near
    BlockRef contour_block;  // the programmed element it comes near (not a neighbour)
    SelfApproachKind kind = SelfApproachKind::kContour;
    double distance = 0.0;   // the least distance found, mm
    double radius = 0.0;     // the tool radius, mm
    Point where = Point::Zero();  // the point of the path, program coordinates
};
// "the tool path of N40 comes within 1.2000 mm of the contour at N90 (tool radius 2.0000 mm):
// ...". The message of the run's warning (or error).
std::string describe(const SelfApproachFinding& f);

// What a check left out: elements let go (from `truncated_at`, in plane `truncated_plane`, each
// element compared only with the window before it), and findings beyond kMaxFindings.
struct SelfApproachLimits {
    bool truncated = false;
    BlockRef truncated_at{};
    int truncated_plane = 17;
    bool capped = false;  // more pairs came near than are reported
};

class SelfApproachCheck {
  public:
    // The elements each is compared with, at least (distinct geometry, per plane), where they
    // take no more than kEntryBudget entries of the grid (an element is listed in each cell of
    // its box, at most four, or of a sample of it every half cell: a tool radius, at least
    // 0.25 mm, of length).
    static constexpr std::size_t kWindow = std::size_t{1} << 16;
    static constexpr std::size_t kEntryBudget = std::size_t{1} << 19;
    // Each pair of blocks is reported once; at most this many pairs.
    static constexpr std::size_t kMaxFindings = 1000;
    // How much closer than the tool radius a path may come: the compensation's path tolerance.
    static constexpr double kTolerance = 1e-4;

    // Where a path's candidates come from: the grid (a stretch that no other comes near kept
    // out of its cells, its own items taken in turn), the grid with every stretch in its cells
    // (a reference for tests: the same questions asked in the same order), or (a reference for
    // tests, quadratic) every element kept, and the same for an element's.
    enum class Candidates { kGrid, kIndexed, kAll };
    // When the calls are worked: a stretch apart from every other, whose own paths keep clear
    // of its own elements, held back (its calls kept, in order) and worked only once a later
    // call could give something out (docs/performance.md, "Stretches held back"): the
    // findings, where and when they are given out, are those of working every call at once
    // (the reference for tests).
    enum class Schedule { kHoldApart, kAtOnce };
    explicit SelfApproachCheck(std::size_t window = kWindow,
                               std::size_t entry_budget = kEntryBudget,
                               Candidates candidates = Candidates::kGrid,
                               Schedule schedule = Schedule::kHoldApart);
    ~SelfApproachCheck();
    SelfApproachCheck(const SelfApproachCheck&) = delete;
    SelfApproachCheck& operator=(const SelfApproachCheck&) = delete;

    // A compensated stretch begins (G41/G42, or the first move after a rapid under G41/G42):
    // tool radius r (mm) in plane 17, 18 or 19, the tool on `side` of the contour (+1 left,
    // G41; -1 right, G42).
    void begin(double r, int plane, int side = 1);
    // Whether the elements programmed from now on may be walls (CDON, the default) or not
    // (CDOF: the program says they are not what it leaves standing; paths are still checked).
    void set_walls(bool on);
    // It ends (G40, a rapid move, the end of the program). Findings against its last element
    // come with the first executed segment after that element's (its departure, or not).
    void end(std::vector<SelfApproachFinding>& out);
    // A line or arc spooled in the stretch, in program order; findings (a path executed
    // before that comes near it) are appended to `out`.
    void programmed(const PathSegment& s, std::vector<SelfApproachFinding>& out);
    // A segment the board executed (every one, in order); findings are appended to `out`.
    void executed(const PathSegment& s, std::vector<SelfApproachFinding>& out);
    // Whether elements were let go (more than 2 * window came in a plane: an element is not
    // compared with those more than `window` distinct elements before it) and where it began,
    // and whether more pairs than kMaxFindings came near (the check then stopped looking).
    SelfApproachLimits limits() const;
    // The elements and paths kept, over all planes, the calls held back counted as items: per
    // plane at most 2 * window elements and 6 * window paths.
    std::size_t kept() const noexcept;
    // The calls held back now (Schedule::kHoldApart), for tests.
    std::size_t held() const noexcept;

  private:
    struct Grid;
    using Shape = detail::Shape;
    // A finding with the numbers of its contour element and of its path's element: whether it
    // is reported depends on what the wall model makes of the element (wall_model.h).
    struct Found {
        SelfApproachFinding f;
        std::uint64_t contour = 0;
        std::uint64_t path = 0;
    };
    struct Pending {
        BlockRef block;
        std::uint64_t index = 0;    // of the element, counted over the whole program
        std::uint64_t stretch = 0;  // of its stretch
        double r = 0.0;
        int plane = 17;
        Eigen::Vector2d end = Eigen::Vector2d::Zero();  // its programmed end, in the plane
    };
    // The programmed elements not yet executed, oldest first, and the one an executed segment
    // belongs to (the check's, and the same kept by the calls held back: hold()).
    class PendingQueue {
      public:
        // Appends p; the oldest is let go where more than kMost wait (never executed: not
        // checked).
        void push(const Pending& p);
        std::size_t waiting() const noexcept { return items_.size() - head_; }
        // Position after the head of the element s belongs to (waiting() where none), see
        // pending_of().
        std::size_t find(const PathSegment& s) const;
        const Pending& at(std::size_t i) const { return items_[head_ + i]; }
        // The head moves on by n (the elements before it are done).
        void advance(std::size_t n);

      private:
        static constexpr std::size_t kMost = 4096;
        void compact();
        std::vector<Pending> items_;
        std::size_t head_ = 0;
    };
    using Pair = std::array<std::uint64_t, 4>;  // (path, contour) blocks: number, line each
    Grid& grid(int plane);
    // The calls as worked (the public calls hand them here, or keep them: Hold).
    void begin_now(double r, int plane, int side);
    void end_now(std::vector<SelfApproachFinding>& out);
    void programmed_now(const PathSegment& s, std::vector<SelfApproachFinding>& out);
    void executed_now(const PathSegment& s, std::vector<SelfApproachFinding>& out);
    // The calls held back and what they must be proved to leave alone (self_approach.cpp).
    struct Hold;
    std::unique_ptr<Hold> hold_;
    // The calls held back worked, in order (none of them gives anything out).
    void release(std::vector<SelfApproachFinding>& out);
    // Nothing found waits to be given out (nor can be: done() is false): a call that brings no
    // pair near gives nothing out.
    bool settled() const;
    // executed()'s steps (self_approach.cpp).
    void leave_undecided(const PathSegment& s, std::size_t at,
                         std::vector<SelfApproachFinding>& out);
    void check_path(const PathSegment& s, const Pending& p, bool running,
                    std::vector<SelfApproachFinding>& out);
    // A path and the part of an element it is held to: the tool radius, the threshold, the
    // element's and the path element's numbers and the element's grid id, and whether only
    // its crossing counts (an approach and an element at its entry point).
    struct Candidate;  // self_approach.cpp
    struct PairView;  // self_approach.cpp
    // A pair the grid brought together that is near enough (near_enough) and whose element
    // may be a wall: dropped where it is given out already or proved apart, held (waiting_)
    // unless the wall model has `placed` both elements, else settled.
    void consider(const PairView& k, bool placed, bool running,
                  std::vector<SelfApproachFinding>& out);
    // Measured, and a finding routed as the stretch rules say (held_, an undecided stretch's
    // held, or given).
    void settle(const PairView& k, bool running, std::vector<SelfApproachFinding>& out);
    // False for a pair given out already.
    bool unreported(const BlockRef& path_block, const BlockRef& contour_block);
    // True with `f` filled when the path comes closer than the threshold to the element (the
    // least distance, and where); false at once for a pair already given out.
    bool measure(const PairView& k, SelfApproachFinding& f);
    static Pair pair_of(const BlockRef& path, const BlockRef& contour);
    SelfApproachFinding* open_finding(const Pair& pair);
    // kMaxFindings pairs were given out, one more came near, and none is open: no later call
    // can change what the check gives out, and it does nothing more.
    bool done() const noexcept { return capped_ && open_.empty(); }
    // The pair was given out (or kMaxFindings were): nothing more of it is looked at.
    bool closed(const Pair& pair);
    // A finding: the least distance of its pair while the pair is open; opened when its path
    // block is still running (more of its segments may come closer), else given out.
    void take(const SelfApproachFinding& f, bool running, std::vector<SelfApproachFinding>& out);
    void flush(std::vector<SelfApproachFinding>& out);  // the open findings go out
    // Findings against the stretch's latest element (its departure, perhaps): merged per pair.
    template <typename Held>
    static void hold(Held& held, const Found& f);
    // A finding the stretch rules let through: reported (take) where the wall model places its
    // element as a wall, dropped where not, held (deferred_) until both elements are placed.
    void give(const Found& f, bool running, std::vector<SelfApproachFinding>& out);
    // The held findings whose elements are placed now.
    void review(std::vector<SelfApproachFinding>& out);
    // A programmed element or an executed path as the grid keeps it (self_approach.cpp), and
    // what the wall model says of its element, kept in it once placed.
    struct GridItem;
    detail::WallRole role_of(GridItem& item);
    bool placed_of(GridItem& item);

    // The wall model lets go of the elements every grid let go of.
    void forget_let_go();
    std::uint64_t forgotten_ = 0;
    // Findings held for the wall model at most; beyond, the oldest is decided as things stand
    // (an element not yet placed counts as a wall).
    static constexpr std::size_t kMaxDeferred = 4096;
    // The first segment after a stretch: decides whether its last element was its departure.
    void leave(const PathSegment& s, std::vector<SelfApproachFinding>& out);

    std::unique_ptr<Grid> grids_[3];
    PendingQueue pending_;  // programmed compensated elements not yet executed
    std::vector<Pair> reported_;    // pairs given out or open, each once
    // Findings of the path block whose segments are coming (current_), the least distance per
    // contour block: given out with the first segment of another block.
    std::vector<SelfApproachFinding> open_;
    BlockRef current_{};  // the block of the last executed segment
    static constexpr std::uint64_t kNone = ~std::uint64_t{0};
    std::size_t window_ = kWindow;
    std::size_t entry_budget_ = kEntryBudget;
    std::vector<Found> held_;  // against latest_, until it is known not the departure
    std::unique_ptr<detail::WallModel> walls_;
    // Both bounded by kMaxDeferred, the oldest let go first (a deque: not a copy of the rest).
    std::deque<Found> deferred_;      // given, waiting for the wall model
    std::deque<Candidate> waiting_;  // unmeasured, waiting for the wall model
    std::uint64_t reviewed_ = 0;   // the wall model's generation at the last review
    // The entry points of the approaches executed (each its element's programmed end, in the
    // plane), by the element's number, oldest first; dropped with the elements let go.
    struct Entry {
        std::uint64_t index;
        Eigen::Vector2d point;
    };
    std::deque<Entry> approach_entries_;
    const Eigen::Vector2d* approach_entry(std::uint64_t index) const;
    std::uint64_t latest_ = kNone;  // grid id (Grid::List numbering) of the stretch's latest
                                    // element of new geometry, in plane_
    // Stretches that ended, oldest first, whose last element (grid id, in `plane`) may be their
    // departure: known from the first segment after that element's (leave()).
    struct Undecided {
        std::uint64_t id = 0;
        std::uint64_t last_index = 0;  // of the stretch's last element
        int plane = 17;
        bool reached = false;  // a segment of the last element was executed
        std::vector<Found> held;  // against it
    };
    std::vector<Undecided> undecided_;
    Undecided* undecided_of(int plane, std::uint64_t id);
    double r_ = 0.0;
    std::uint64_t stretch_ = 0;
    std::uint64_t next_index_ = 0;
    // The small fields together, after the large ones (no padding between those).
    Candidates candidates_ = Candidates::kGrid;
    int plane_ = 17;
    bool capped_ = false;  // see done()
    bool seen_ = false;    // a segment was executed
    bool walls_on_ = true;
    bool first_in_stretch_ = false;
    bool active_ = false;
};

}  // namespace apci::run
