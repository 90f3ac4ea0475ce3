// SPDX-License-Identifier: MIT
// Which programmed elements are walls: the part of the contour a program leaves standing, which
// the tool must keep its radius from (docs/compensation.md, "What is a wall"). The self-approach
// check (self_approach.h) asks this model before it reports a path coming near an element.
//
// A compensated stretch (G41/G42 to G40) is read as a CAM system writes it: leads onto and off
// the contour, and the contour as closed loops. A loop closes where an element ends at the start
// of an earlier element of the stretch (after the last loop); the (up to two) elements before a
// stretch's first loop (the lead-in), after a loop (the lead-out, or the way to the next pass)
// and before the next loop are leads: they lie where the tool only passes, and are no walls.
// Other elements outside the loops, and every element of a stretch without a loop, are an open
// contour's: walls (the check leaves out a stretch's approach and departure by its own rules). A loop the tool runs inside (a
// pocket's pass) is cleared, no wall, where a larger pocket pass of the same plane and level
// encloses it: the material beyond it is taken away by that pass (a pocket widened in passes,
// a pocket cleared in stepovers from the inside out or from the outside in); a loop the tool runs
// outside of (a boss) is cleared where it encloses a smaller boss pass of the same plane and
// level (the roughing passes round a part). Islands and pockets, or bosses side by side, never
// clear each other. Elements programmed under CDOF are no walls either (the program says that
// what follows is not what it leaves standing).
#pragma once

#include <cstdint>
#include <deque>
#include <unordered_map>
#include <vector>

#include "apci/run/plane_distance.h"
#include "contour_loop.h"
#include "probe_table.h"

namespace apci::run::detail {

enum class WallRole : std::uint8_t {
    kUndecided,  // its stretch runs and no loop closed through it yet
    kWall,       // part of what the program leaves standing
    kLead,       // a lead-in, a lead-out or a connection between loops
    kCleared,    // in a loop that another pass clears
    kOff,        // programmed under CDOF
};

// A programmed move in the plane as the model takes it: its ends, and an arc's centre and sense
// (its radii and angles are worked out only for a loop the model has not seen before, unless
// the caller has them: `terms`, an arc's sweep and start angle as plane::arc_element gives them
// for the same numbers), and its extent on the plane's third axis.
struct PlaneMove {
    plane::Vec2 start = plane::Vec2::Zero(), end = plane::Vec2::Zero();
    plane::Vec2 centre = plane::Vec2::Zero();
    bool arc = false;
    bool ccw = false;
    bool terms = false;
    double sweep = 0.0, phi0 = 0.0;
    double low = 0.0, high = 0.0;
};

class WallModel {
  public:
    // What a model is asked: roles (a loop's clearing among them), or only where the elements
    // are placed (placement(): leads, CDOF, loops' and open contours' elements), for which it
    // keeps nothing of the loops (their geometry, levels and index: role() takes every loop's
    // element for a wall, cleared() is false).
    enum class Asks : std::uint8_t { kRoles, kPlacement };
    explicit WallModel(Asks asks = Asks::kRoles) : asks_(asks) {}

    // Two loops' elements closer than this touch (a pass widened on some sides only), and
    // an end this close to an earlier start closes a loop; levels overlap within it.
    static constexpr double kTolerance = 1e-4;
    // Element pairs one test of enclosure may take: larger loops are not compared (each stays
    // a wall).
    static constexpr long kPairBudget = 1L << 20;
    // A lead is at most this many elements next to its loop: a line and an arc, as CAM systems
    // write leads onto and off a contour (a straight line, a tangent arc, or both).
    static constexpr std::size_t kLeadElements = 2;
    // The loops are listed in the cells (of kLoopCell mm) their box covers, or, where that
    // is more than kLoopCells, in a list of wide loops that every search looks at.
    static constexpr double kLoopCell = 16.0;
    static constexpr std::int64_t kLoopCells = 256;
    // Elements of a stretch that may still begin a loop: an older one is an open contour's
    // (a loop of more elements is not seen as one).
    static constexpr std::size_t kMaxPending = std::size_t{1} << 14;

    // A stretch begins in `plane` (17, 18, 19) with the tool on `side` (+1 left, G41; -1 right).
    void begin(int plane, int side);
    // The stretch's next element that moves in the plane, in program order: the check's number
    // for it (increasing over the program), its geometry in the plane, its extent on the
    // plane's third axis, the key of its geometry (the same for the same numbers), and whether
    // walls are on (CDON) where it is programmed.
    // `repeat`: its geometry came before (the check asks only about the first element of each
    // geometry: the model keeps no record of a repeat once it is placed).
    void element(std::uint64_t index, const PlaneMove& e, std::uint64_t key, bool walls,
                 bool repeat);
    // The stretch ends: what came after its last loop is its lead-out; without a loop it is an
    // open contour.
    void end();
    // True once what the element is can be decided: its stretch ended (every loop of it is
    // known: a pocket's later, larger passes in the same stretch clear its earlier ones). An
    // element an open contour's long stretch let go of (kMaxPending) is placed too, and so are
    // elements the model does not hold (never given, or forgotten).
    bool placed(std::uint64_t index) const;
    // True when the element is one of a loop's.
    bool looped(std::uint64_t index) const;
    // What is known of a placed element without deciding its loop: kUndecided (not placed),
    // kLead, kOff, or kWall with `loop` its loop's number (or kNoLoop for an open contour's).
    // A caller that keeps the answer asks cleared(loop) for the rest.
    static constexpr std::uint64_t kNoLoop = ~std::uint64_t{0};
    WallRole placement(std::uint64_t index, std::uint64_t& loop) const;
    // Whether the loop numbered `number` is cleared by a loop known now (decided once, then kept).
    bool cleared(std::uint64_t number);
    // Its role as known now: a loop's element is a wall unless a loop known now clears it.
    WallRole role(std::uint64_t index);
    // Lets go of the elements numbered below `index`, and of the loops all of whose
    // occurrences lie below it.
    void forget_before(std::uint64_t index);
    // Grows whenever elements are placed: their stretch ended, or an open contour's element.
    std::uint64_t generation() const noexcept { return generation_; }
    // The loops held (for tests and the memory bound).
    std::size_t loops() const noexcept { return loops_.size() - loops_dropped_; }

  private:
    enum class Place : std::uint8_t { kUndecided, kLead, kLoop, kOpen };
    // What the model keeps of an element until it is placed, and after that only what differs
    // from an element it does not hold (placed, a wall): a loop's, a lead's or one under CDOF
    // of geometry not seen before (the check asks about the first element of each geometry).
    struct Record {
        std::uint64_t index = 0;
        std::uint64_t loop = 0;  // kLoop: its loop's number
        Place place = Place::kUndecided;
        bool walls = true;
        bool repeat = false;  // its geometry came before
    };
    struct Pending {
        std::uint64_t index;
        PlaneMove move;
        std::uint64_t key;
    };
    struct Loop {
        int plane = 17;
        int sense = 0;  // +1 the tool inside it (a pocket), -1 outside (a boss), 0 no area
        double low = 0.0, high = 0.0;
        std::uint64_t last = 0;  // the highest element number of any of its occurrences
        std::uint64_t key = 0;   // of its elements' geometry, in any order
        // Its elements, kept packed (a program's loops hold as many elements as the program):
        // made plane::Parametrics again where an enclosure is tested (clears()).
        struct Kept {
            double start[2], end[2], centre[2];
            bool arc, ccw;
        };
        std::vector<Kept> elements;
        plane::Bounds box;
        bool cleared = false;
        std::size_t known = 0;  // loops there were when it was last decided
        bool dropped = false;
    };
    // Keeps the loop of the pending elements from `from` on (its geometry, or the same loop's
    // levels joined): its number.
    std::uint64_t keep_loop(std::size_t from);
    void index_loop(std::uint64_t number);
    // The loops that may clear `loop`: those whose box holds its box's centre (a pocket pass
    // enclosing it), or whose box's centre its box holds (a boss pass it encloses).
    void candidates(const Loop& loop, std::vector<std::uint64_t>& out);
    // Relists the loops kept (after some were let go).
    void reindex_loops();
    CellIndex<1> loop_cells_;  // loop numbers less loops_first_
    std::vector<std::uint64_t> wide_loops_;
    std::vector<std::uint32_t> cell_found_;
    std::vector<std::uint64_t> found_;  // candidates()' answer
    Record* record(std::uint64_t index);
    const Record* record(std::uint64_t index) const;
    // Where the last lookup found its record: the next lookups are mostly of it or the one
    // after (elements placed in order, grid items asked in order), found without a search.
    mutable std::size_t hint_ = 0;
    // The open stretch's elements wait for its end, but for an open contour's placed at once.
    bool waits(std::uint64_t index) const {
        return open_ && started_ && index >= stretch_first_ && !opened_early_;
    }
    // placed() with the element's record looked up (null: not held).
    bool placed(std::uint64_t index, const Record* r) const;
    void place_pending(std::size_t count, Place place, std::uint64_t loop);
    void place_run(std::size_t count, bool after_loop, bool before_loop);
    // The position in records_ of the first record numbered `index` or later.
    std::size_t tail_of(std::uint64_t index) const;
    void clear_pending();
    // Up to this many pending elements are searched one by one for a start; beyond, by cells.
    static constexpr std::size_t kScanned = 64;
    void close_loop(std::size_t from);
    bool clears(const Loop& outer_pass, const Loop& loop) const;
    // A loop's elements as plane::Parametrics, in `out`.
    static void elements_of(const Loop& loop, std::vector<plane::Parametric>& out);
    // A move as a plane::Parametric: the same numbers as plane::arc_element's (or line_element's)
    // of its ends, centre and sense, its arc terms taken where it has them.
    static plane::Parametric parametric_of(const PlaneMove& m);
    void decide(Loop& loop, std::uint64_t number);

    // Drops the records placed since `from` (an index into records_) that say nothing more.
    void prune(std::size_t from);
    std::vector<Record> records_;  // by element number, ascending
    std::size_t records_head_ = 0;  // records before it were forgotten
    std::vector<Loop> loops_;       // numbered from loops_first_
    std::uint64_t loops_first_ = 0;
    std::size_t loops_dropped_ = 0;
    Asks asks_ = Asks::kRoles;
    std::size_t live_ = 0;  // loops_[k] for k < live_ are all dropped
    std::size_t unindexed_ = 0;  // loops dropped since the index was last made
    // The loop of each geometry key (its number; a key of a loop let go finds it dropped).
    ProbeTable<std::uint64_t> loop_by_key_;
    // The stretch under way.
    int plane_ = 17;
    int side_ = 1;
    bool open_ = false;
    int stretch_loops_ = 0;
    std::uint64_t stretch_first_ = 0;  // the number of the open stretch's first element
    bool started_ = false;             // it has one
    bool opened_early_ = false;        // an element of it was placed as an open contour's
    std::deque<Pending> pending_;  // since the last loop closed (the oldest let go: kMaxPending)
    // Where there are many pending elements: the pending elements (each its number in the
    // stretch since the last loop, pending_first_ + position) starting in each cell of
    // kTolerance (key of the quantised point).
    std::unordered_multimap<std::uint64_t, std::uint64_t> starts_;
    // Records of elements let go from pending_ as an open contour's (kMaxPending) since the
    // last prune: pruned together, not each (that would scan every pending element's record).
    std::size_t stale_ = 0;
    std::uint64_t pending_first_ = 0;  // the stretch's count of elements before pending_[0]
    std::uint64_t generation_ = 0;
    // Scratch for the elements of the loops an enclosure test compares (memory kept).
    mutable std::vector<plane::Parametric> elements_, inner_elements_;
};

}  // namespace apci::run::detail
