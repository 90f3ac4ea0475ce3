// SPDX-License-Identifier: MIT
#include "wall_model.h"

#include <algorithm>
#include <cmath>

#include "contour_loop.h"

namespace apci::run::detail {
namespace {

std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 31;
    x *= 0x9E3779B97F4A7C15ULL;
    return x ^ (x >> 29);
}

// The cell of 1e-4 mm (WallModel::kTolerance) a point lies in, as one key.
std::int64_t cell_of(double v) {
    return static_cast<std::int64_t>(std::floor(v / WallModel::kTolerance));
}

}  // namespace

void WallModel::begin(int plane, int side) {
    if (open_) end();
    open_ = true;
    plane_ = plane;
    side_ = side < 0 ? -1 : 1;
    stretch_loops_ = 0;
    started_ = false;
    opened_early_ = false;
    clear_pending();
}

void WallModel::clear_pending() {
    pending_.clear();
    starts_.clear();
    pending_first_ = 0;
}

void WallModel::element(std::uint64_t index, const PlaneMove& e, std::uint64_t key, bool walls,
                        bool repeat) {
    if (!open_) return;
    if (pending_.empty() && stretch_loops_ == 0 && !started_) {
        stretch_first_ = index;
        started_ = true;
    }
    records_.push_back(Record{index, 0, Place::kUndecided, walls, repeat});
    // The oldest pending element can no longer begin a loop: an open contour's, placed at once
    // (as place_pending places it). Its record, which says nothing more, goes with the next
    // prune of all such records.
    if (pending_.size() >= kMaxPending) {
        const Pending& oldest = pending_.front();
        if (Record* r = record(oldest.index)) {
            r->place = Place::kOpen;
            r->loop = 0;
        }
        ++generation_;
        opened_early_ |= open_;
        if (!starts_.empty()) {
            const auto [lo, hi] = starts_.equal_range(
                cell_key(cell_of(oldest.move.start.x()), cell_of(oldest.move.start.y())));
            for (auto it = lo; it != hi; ++it)
                if (it->second == pending_first_) {
                    starts_.erase(it);
                    break;
                }
        }
        pending_.pop_front();
        ++pending_first_;
        if (++stale_ >= kMaxPending) {
            prune(records_head_);
            stale_ = 0;
        }
    }
    pending_.push_back(Pending{index, e, key});
    const std::uint64_t number = pending_first_ + pending_.size() - 1;
    const bool hashed = pending_.size() > kScanned;
    if (hashed) {
        if (starts_.empty())  // the pending elements so far
            for (std::size_t i = 0; i < pending_.size(); ++i)
                starts_.emplace(cell_key(cell_of(pending_[i].move.start.x()),
                                         cell_of(pending_[i].move.start.y())),
                                pending_first_ + i);
        else
            starts_.emplace(cell_key(cell_of(e.start.x()), cell_of(e.start.y())), number);
    }
    // Does it end where an element since the last loop started? The earliest such one.
    std::size_t from = pending_.size();
    const auto closes_at = [&](const Pending& p) {
        return (p.move.start - e.end).squaredNorm() <= kTolerance * kTolerance;
    };
    if (!hashed) {
        // The first that does, walked with an iterator (a deque's [] costs a division).
        std::size_t i = 0;
        for (auto it = pending_.begin(); it != pending_.end(); ++it, ++i)
            if (closes_at(*it)) {
                from = i;
                break;
            }
    } else {
        const auto consider = [&](std::size_t at) {
            if (at < from && closes_at(pending_[at])) from = at;
        };
        const std::int64_t ci = cell_of(e.end.x()), cj = cell_of(e.end.y());
        for (std::int64_t i = ci - 1; i <= ci + 1; ++i)
            for (std::int64_t j = cj - 1; j <= cj + 1; ++j) {
                const auto [lo, hi] = starts_.equal_range(cell_key(i, j));
                for (auto it = lo; it != hi; ++it)
                    if (it->second >= pending_first_)
                        consider(static_cast<std::size_t>(it->second - pending_first_));
            }
    }
    if (from < pending_.size()) close_loop(from);
}

std::uint64_t WallModel::keep_loop(std::size_t from) {
    Loop loop;
    loop.plane = plane_;
    loop.low = pending_[from].move.low;
    loop.high = pending_[from].move.high;
    std::uint64_t key = 0x5851F42D4C957F2DULL + static_cast<std::uint64_t>(plane_);
    for (auto it = pending_.begin() + static_cast<std::ptrdiff_t>(from); it != pending_.end();
         ++it) {
        const Pending& p = *it;
        loop.low = std::min(loop.low, p.move.low);
        loop.high = std::max(loop.high, p.move.high);
        key += mix(p.key);  // the same elements in any order: the same loop
    }
    loop.last = pending_.back().index;
    loop.key = key;
    // The same contour run again (at another depth, from another corner): one loop, its levels
    // joined.
    std::uint64_t number = 0;
    const std::uint64_t* same = loop_by_key_.get(key);
    if (same != nullptr && *same >= loops_first_ &&
        !loops_[static_cast<std::size_t>(*same - loops_first_)].dropped) {
        number = *same;
        Loop& l = loops_[static_cast<std::size_t>(number - loops_first_)];
        l.low = std::min(l.low, loop.low);
        l.high = std::max(l.high, loop.high);
        l.last = std::max(l.last, loop.last);
    } else {
        loop.elements.reserve(pending_.size() - from);
        for (std::size_t i = from; i < pending_.size(); ++i) {
            const PlaneMove& m = pending_[i].move;
            loop.elements.push_back(Loop::Kept{{m.start.x(), m.start.y()},
                                               {m.end.x(), m.end.y()},
                                               {m.centre.x(), m.centre.y()},
                                               m.arc,
                                               m.ccw});
        }
        std::vector<plane::Parametric>& elements = elements_;
        elements.clear();
        for (std::size_t i = from; i < pending_.size(); ++i)
            elements.push_back(parametric_of(pending_[i].move));
        const double area = plane::signed_area(elements);
        // A loop with no area to speak of (out and back along itself) has no inside.
        const double scale = std::max(1.0, std::abs(area));
        if (std::abs(area) > 1e-9 * scale && std::abs(area) > 1e-12)
            loop.sense = (area > 0.0 ? 1 : -1) * side_;
        number = loops_first_ + loops_.size();
        loop.box = plane::bounds(elements);
        loops_.push_back(std::move(loop));
        loop_by_key_.emplace(key).first = number;
        index_loop(number);
    }
    return number;
}

void WallModel::close_loop(std::size_t from) {
    // A model asked only where elements are placed keeps nothing of the loop.
    const std::uint64_t number = asks_ == Asks::kPlacement ? kNoLoop : keep_loop(from);
    place_run(from, stretch_loops_ > 0, true);
    const std::size_t members = pending_.size() - from;
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(from));
    place_pending(members, Place::kLoop, number);
    clear_pending();
    ++stretch_loops_;
}

// The first `count` pending elements, a run outside the loops: up to kLeadElements of it next
// to a loop before it (`after_loop`) and next to one after it (`before_loop`) are leads, the
// rest an open contour's elements.
void WallModel::place_run(std::size_t count, bool after_loop, bool before_loop) {
    const std::size_t tail = count > 0 ? tail_of(pending_[0].index) : records_.size();
    bool opened = false;
    auto it = pending_.begin();
    for (std::size_t i = 0; i < count; ++i, ++it) {
        const bool lead = (after_loop && i < kLeadElements) ||
                          (before_loop && count - i <= kLeadElements);
        Record* r = record(it->index);
        if (r == nullptr) continue;
        r->place = lead ? Place::kLead : Place::kOpen;
        if (!lead) opened = true;
    }
    if (opened) {
        ++generation_;
        opened_early_ |= open_;
    }  // an open contour's element is placed at once
    prune(tail);
}

// The first `count` pending elements are placed (their records are the latest undecided ones,
// in the same order).
void WallModel::place_pending(std::size_t count, Place place, std::uint64_t loop) {
    const std::size_t tail = count > 0 ? tail_of(pending_[0].index) : records_.size();
    auto it = pending_.begin();
    for (std::size_t i = 0; i < count; ++i, ++it) {
        Record* r = record(it->index);
        if (r == nullptr) continue;
        r->place = place;
        r->loop = loop;
    }
    if (count > 0 && place == Place::kOpen) {  // placed at once
        ++generation_;
        opened_early_ |= open_;
    }
    prune(tail);
}

std::size_t WallModel::tail_of(std::uint64_t index) const {
    const auto begin = records_.begin() + static_cast<std::ptrdiff_t>(records_head_);
    return static_cast<std::size_t>(
        std::lower_bound(begin, records_.end(), index,
                         [](const Record& r, std::uint64_t i) { return r.index < i; }) -
        records_.begin());
}

void WallModel::prune(std::size_t from) {
    const auto gone = [](const Record& r) {
        if (r.place == Place::kUndecided) return false;
        return r.repeat || (r.place == Place::kOpen && r.walls);
    };
    const auto begin = records_.begin() + static_cast<std::ptrdiff_t>(from);
    records_.erase(std::remove_if(begin, records_.end(), gone), records_.end());
}

void WallModel::end() {
    if (!open_) return;
    place_run(pending_.size(), stretch_loops_ > 0, false);
    clear_pending();
    open_ = false;
    ++generation_;  // the stretch's elements are placed now
}

WallModel::Record* WallModel::record(std::uint64_t index) {
    return const_cast<Record*>(static_cast<const WallModel*>(this)->record(index));
}

const WallModel::Record* WallModel::record(std::uint64_t index) const {
    for (std::size_t at = hint_; at < hint_ + 2 && at < records_.size(); ++at)
        if (at >= records_head_ && records_[at].index == index) {
            hint_ = at;
            return &records_[at];
        }
    const auto begin = records_.begin() + static_cast<std::ptrdiff_t>(records_head_);
    const auto it = std::lower_bound(begin, records_.end(), index,
                                     [](const Record& r, std::uint64_t i) { return r.index < i; });
    if (it == records_.end() || it->index != index) return nullptr;
    hint_ = static_cast<std::size_t>(it - records_.begin());
    return &*it;
}

bool WallModel::placed(std::uint64_t index) const {
    if (waits(index)) return false;
    return placed(index, record(index));
}

bool WallModel::placed(std::uint64_t index, const Record* r) const {
    if (r == nullptr) return true;
    if (r->place == Place::kUndecided) return false;
    return !(open_ && index >= stretch_first_) || r->place == Place::kOpen;
}

bool WallModel::looped(std::uint64_t index) const {
    const Record* r = record(index);
    return r != nullptr && r->place == Place::kLoop;
}

bool WallModel::clears(const Loop& pass, const Loop& loop) const {
    if (pass.dropped || pass.plane != loop.plane || pass.sense != loop.sense || loop.sense == 0)
        return false;
    if (pass.low > loop.high + kTolerance || pass.high < loop.low - kTolerance) return false;
    // A pocket pass clears the pockets it encloses; a boss pass clears the bosses round it.
    const Loop& outer = loop.sense > 0 ? pass : loop;
    const Loop& inner = loop.sense > 0 ? loop : pass;
    // The boxes first (within() tests them too): the elements are made only where they hold.
    if ((inner.box.lo.array() < outer.box.lo.array() - kTolerance).any() ||
        (inner.box.hi.array() > outer.box.hi.array() + kTolerance).any())
        return false;
    elements_of(outer, elements_);
    elements_of(inner, inner_elements_);
    return plane::within(elements_, outer.box, inner_elements_, inner.box, kTolerance,
                         kPairBudget) == plane::Within::kWithin;
}

void WallModel::elements_of(const Loop& loop, std::vector<plane::Parametric>& out) {
    out.clear();
    for (const Loop::Kept& k : loop.elements) {
        const plane::Vec2 start(k.start[0], k.start[1]), end(k.end[0], k.end[1]);
        out.push_back(k.arc ? plane::arc_element(start, end, {k.centre[0], k.centre[1]}, k.ccw)
                            : plane::line_element(start, end));
    }
}

plane::Parametric WallModel::parametric_of(const PlaneMove& m) {
    if (!m.arc) return plane::line_element(m.start, m.end);
    if (!m.terms) return plane::arc_element(m.start, m.end, m.centre, m.ccw);
    return plane::arc_element(m.start, m.end, m.centre, m.ccw, m.sweep, m.phi0);
}

void WallModel::decide(Loop& loop, std::uint64_t number) {
    if (loop.cleared || loop.known == loops_.size() + loops_first_) return;
    loop.known = loops_.size() + loops_first_;
    candidates(loop, found_);
    for (const std::uint64_t other : found_) {
        if (other == number || other < loops_first_) continue;
        if (clears(loops_[static_cast<std::size_t>(other - loops_first_)], loop)) {
            loop.cleared = true;
            return;
        }
    }
}

namespace {
std::int64_t loop_cell(double v) {
    return static_cast<std::int64_t>(std::floor(v / WallModel::kLoopCell));
}
}  // namespace

void WallModel::index_loop(std::uint64_t number) {
    const Loop& l = loops_[static_cast<std::size_t>(number - loops_first_)];
    const std::int64_t i0 = loop_cell(l.box.lo.x()), i1 = loop_cell(l.box.hi.x());
    const std::int64_t j0 = loop_cell(l.box.lo.y()), j1 = loop_cell(l.box.hi.y());
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > kLoopCells) {
        wide_loops_.push_back(number);
        return;
    }
    const auto item = static_cast<std::uint32_t>(number - loops_first_);
    for (std::int64_t i = i0; i <= i1; ++i)
        for (std::int64_t j = j0; j <= j1; ++j) loop_cells_.add(0, cell_key(i, j), item);
}

void WallModel::reindex_loops() {
    unindexed_ = 0;
    loop_cells_.clear();
    wide_loops_.clear();
    loop_by_key_.clear();
    for (std::size_t k = live_; k < loops_.size(); ++k) {
        if (loops_[k].dropped) continue;
        index_loop(loops_first_ + k);
        loop_by_key_.emplace(loops_[k].key).first = loops_first_ + k;
    }
}

void WallModel::candidates(const Loop& loop, std::vector<std::uint64_t>& out) {
    out.assign(wide_loops_.begin(), wide_loops_.end());
    const plane::Vec2 centre = 0.5 * (loop.box.lo + loop.box.hi);
    const std::int64_t i0 = loop_cell(loop.box.lo.x()), i1 = loop_cell(loop.box.hi.x());
    const std::int64_t j0 = loop_cell(loop.box.lo.y()), j1 = loop_cell(loop.box.hi.y());
    const auto add_cell = [&](std::int64_t i, std::int64_t j) {
        cell_found_.clear();
        loop_cells_.append(0, cell_key(i, j), cell_found_);
        for (const std::uint32_t item : cell_found_) out.push_back(loops_first_ + item);
    };
    if (loop.sense > 0) {
        add_cell(loop_cell(centre.x()), loop_cell(centre.y()));
    } else if ((i1 - i0 + 1) * (j1 - j0 + 1) > kLoopCells) {
        out.clear();
        for (std::size_t k = live_; k < loops_.size(); ++k) out.push_back(loops_first_ + k);
    } else {
        for (std::int64_t i = i0; i <= i1; ++i)
            for (std::int64_t j = j0; j <= j1; ++j) add_cell(i, j);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

WallRole WallModel::placement(std::uint64_t index, std::uint64_t& loop) const {
    loop = kNoLoop;
    if (waits(index)) return WallRole::kUndecided;
    const Record* r = record(index);
    if (!placed(index, r)) return WallRole::kUndecided;
    if (r == nullptr) return WallRole::kWall;
    if (!r->walls) return WallRole::kOff;
    if (r->place == Place::kLead) return WallRole::kLead;
    if (r->place == Place::kLoop) loop = r->loop;
    return WallRole::kWall;
}

bool WallModel::cleared(std::uint64_t number) {
    if (number < loops_first_ || number - loops_first_ >= loops_.size()) return false;
    Loop& loop = loops_[static_cast<std::size_t>(number - loops_first_)];
    if (loop.dropped) return false;
    decide(loop, number);
    return loop.cleared;
}

WallRole WallModel::role(std::uint64_t index) {
    if (waits(index)) return WallRole::kUndecided;
    const Record* r = record(index);
    if (!placed(index, r)) return WallRole::kUndecided;
    if (r == nullptr) return WallRole::kWall;
    if (!r->walls) return WallRole::kOff;
    switch (r->place) {
        case Place::kLead:
            return WallRole::kLead;
        case Place::kOpen:
            return WallRole::kWall;
        case Place::kLoop: {
            if (r->loop < loops_first_ || r->loop - loops_first_ >= loops_.size())
                return WallRole::kWall;
            Loop& loop = loops_[static_cast<std::size_t>(r->loop - loops_first_)];
            if (loop.dropped) return WallRole::kWall;
            decide(loop, r->loop);
            return loop.cleared ? WallRole::kCleared : WallRole::kWall;
        }
        case Place::kUndecided:
            break;
    }
    return WallRole::kUndecided;
}

void WallModel::forget_before(std::uint64_t index) {
    while (records_head_ < records_.size() && records_[records_head_].index < index &&
           records_[records_head_].place != Place::kUndecided)
        ++records_head_;
    if (records_head_ > 1024 && 2 * records_head_ > records_.size()) {
        records_.erase(records_.begin(), records_.begin() + static_cast<std::ptrdiff_t>(records_head_));
        records_head_ = 0;
    }
    // Loops before live_ are all dropped: only those from it on may be let go now.
    for (std::size_t k = live_; k < loops_.size(); ++k) {
        Loop& l = loops_[k];
        if (!l.dropped && l.last < index) {
            l.dropped = true;
            l.elements = {};
            ++loops_dropped_;
            ++unindexed_;
        }
    }
    while (live_ < loops_.size() && loops_[live_].dropped) ++live_;
    // Loops let go at the front are forgotten (numbers stay as they were).
    if (live_ > 1024 && 2 * live_ > loops_.size()) {
        loops_.erase(loops_.begin(), loops_.begin() + static_cast<std::ptrdiff_t>(live_));
        loops_first_ += live_;
        loops_dropped_ -= live_;
        live_ = 0;
        reindex_loops();  // the index's numbers changed
        return;
    }
    // A dropped loop left in the index is passed over where it is found (clears(), the key's
    // lookup in close_loop()); the index is made again once they outnumber the loops kept, so
    // that each drop costs the index a share of one remaking.
    if (unindexed_ > std::max<std::size_t>(64, loops())) reindex_loops();
}

}  // namespace apci::run::detail
