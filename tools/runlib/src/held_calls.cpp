// SPDX-License-Identifier: MIT
// The hold's calls written compactly (held_calls.h).
#include "held_calls.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>

namespace apci::run::detail {

namespace {

// A record: a header of kHeaderBytes, then the numbers its flags say are there, in this order:
// the plane (kPlaneWide), the block (none of kSameBlock, kNextBlock, kNextNumber), the start (not
// kStartIsLast), the end's coordinates not in `same_as_start` (bits 0-2: the start's), the
// centre's not in it (bits 3-5: the start's) where kCentre, the sweep (kSweep); a kBegin its
// radius.
enum Flag : std::uint8_t {
    kCcw = 1,
    kStartIsLast = 2,  // the start is the end of the last segment of its kind
    kSameBlock = 4,    // the block is the last segment's of its kind
    kCentre = 8,       // the centre is not 0, 0, 0: its coordinates not the start's are written
    kSweep = 16,       // the sweep is written (else kSweepZero: 0; neither: a quiet NaN)
    kSweepZero = 32,
    kNextBlock = 64,    // the block's number and line are the last one's of its kind, plus one
    kNextNumber = 128,  // the block's number is the last one's plus one, its line the same (an
                        // executed segment carries a block's number alone)
};
// The flags of the other records.
constexpr std::uint8_t kOn = 1;            // kWalls
constexpr std::uint8_t kSideNegative = 1;  // kBegin
constexpr std::size_t kHeaderBytes = 6;    // kind, segment kind, role, flags, same_as_start, plane
constexpr std::uint8_t kPlaneWide = 3;     // plane code: an int32 plane follows

std::uint8_t plane_code(int plane) {
    return plane == 17 ? 0 : plane == 18 ? 1 : plane == 19 ? 2 : kPlaneWide;
}
int plane_of(std::uint8_t code) {
    return 17 + code;
}

bool zero_bits(const Point& p) {
    return same_bits(p, Point::Zero());
}

template <class T>
std::byte* put(std::byte* at, const T& v) {
    std::memcpy(at, &v, sizeof v);
    return at + sizeof v;
}
template <class T>
const std::byte* get(const std::byte* at, T& v) {
    std::memcpy(&v, at, sizeof v);
    return at + sizeof v;
}
std::byte* put_point(std::byte* at, const Point& p) {
    for (int i = 0; i < 3; ++i) at = put(at, p[i]);
    return at;
}
const std::byte* get_point(const std::byte* at, Point& p) {
    for (int i = 0; i < 3; ++i) at = get(at, p[i]);
    return at;
}

std::size_t slot_of(HeldCall::Kind k) {
    return k == HeldCall::Kind::kExecuted ? 1 : 0;
}

}  // namespace

HeldCalls::HeldCalls(std::size_t chunk_bytes) : chunk_bytes_(std::max(chunk_bytes, kMostRecord)) {}

HeldCalls::HeldCalls(Slab& memory) : chunk_bytes_(Slab::kMostTaken), chunks_(memory) {}

std::byte* HeldCalls::room() {
    if (chunks_.empty() || used_[current_] + kMostRecord > chunk_bytes_) {
        const std::size_t next = chunks_.empty() ? 0 : current_ + 1;
        if (next == chunks_.size()) {
            // Room first, and the chunk taken last: where none can be had (std::bad_alloc),
            // nothing has changed.
            used_.reserve(used_.size() + 1);
            ready_.reserve(ready_.size() + 1);
            chunks_.add(chunk_bytes_);
            used_.push_back(0);
            ready_.emplace_back();
        }
        current_ = next;
    }
    std::byte* const chunk = chunks_[current_];
    if (!chunks_.carved())
        ready_[current_].before_write(chunk, used_[current_], kMostRecord, chunk_bytes_);
    return chunk + used_[current_];
}

void HeldCalls::wrote(std::byte* end) {
    used_[current_] = static_cast<std::size_t>(end - chunks_[current_]);
    ++count_;
}

void HeldCalls::begin(double radius, int plane, int side) {
    std::byte* at = room();
    const std::uint8_t code = plane_code(plane);
    const std::uint8_t header[kHeaderBytes] = {
        static_cast<std::uint8_t>(HeldCall::Kind::kBegin),       0, 0,
        static_cast<std::uint8_t>(side < 0 ? kSideNegative : 0), 0, code};
    at = put(at, header);
    if (code == kPlaneWide) at = put(at, static_cast<std::int32_t>(plane));
    wrote(put(at, radius));
}

void HeldCalls::end() {
    std::byte* at = room();
    const std::uint8_t header[kHeaderBytes] = {static_cast<std::uint8_t>(HeldCall::Kind::kEnd)};
    wrote(put(at, header));
}

void HeldCalls::walls(bool on) {
    std::byte* at = room();
    const std::uint8_t header[kHeaderBytes] = {static_cast<std::uint8_t>(HeldCall::Kind::kWalls), 0,
                                               0, static_cast<std::uint8_t>(on ? kOn : 0)};
    wrote(put(at, header));
}

void HeldCalls::segment(HeldCall::Kind kind, const PathSegment& s) {
    std::byte* at = room();
    const std::size_t k = slot_of(kind);
    std::uint8_t flags = s.ccw ? kCcw : 0;
    const BlockRef& last = last_.block[k];
    if (last_.has[k] && same_bits(s.start, last_.end[k])) flags |= kStartIsLast;
    if (last_.has[k] && s.block.number == last.number && s.block.line == last.line)
        flags |= kSameBlock;
    else if (last_.has[k] && last.number < std::numeric_limits<std::int64_t>::max() &&
             s.block.number == last.number + 1) {
        if (s.block.line == last.line)
            flags |= kNextNumber;
        else if (last.line < std::numeric_limits<std::uint64_t>::max() &&
                 s.block.line == last.line + 1)
            flags |= kNextBlock;
    }
    if (!zero_bits(s.center)) flags |= kCentre;
    if (same_bits(s.sweep, 0.0))
        flags |= kSweepZero;
    else if (!same_bits(s.sweep, std::numeric_limits<double>::quiet_NaN()))
        flags |= kSweep;
    std::uint8_t same_as_start = 0;
    for (int i = 0; i < 3; ++i) {
        if (same_bits(s.end[i], s.start[i])) same_as_start |= static_cast<std::uint8_t>(1u << i);
        if (same_bits(s.center[i], s.start[i])) same_as_start |= static_cast<std::uint8_t>(8u << i);
    }
    const std::uint8_t code = plane_code(s.plane);
    const std::uint8_t header[kHeaderBytes] = {static_cast<std::uint8_t>(kind),
                                               static_cast<std::uint8_t>(s.kind),
                                               static_cast<std::uint8_t>(s.role),
                                               flags,
                                               same_as_start,
                                               code};
    at = put(at, header);
    if (code == kPlaneWide) at = put(at, static_cast<std::int32_t>(s.plane));
    if ((flags & (kSameBlock | kNextBlock | kNextNumber)) == 0) {
        at = put(at, s.block.number);
        at = put(at, s.block.line);
    }
    if ((flags & kStartIsLast) == 0) at = put_point(at, s.start);
    for (int i = 0; i < 3; ++i)
        if ((same_as_start & (1u << i)) == 0) at = put(at, s.end[i]);
    if ((flags & kCentre) != 0)
        for (int i = 0; i < 3; ++i)
            if ((same_as_start & (8u << i)) == 0) at = put(at, s.center[i]);
    if ((flags & kSweep) != 0) at = put(at, s.sweep);
    wrote(at);
    last_.end[k] = s.end;
    last_.block[k] = s.block;
    last_.has[k] = true;
}

bool HeldCalls::Reader::next(HeldCall& c) {
    if (read_ == calls_.count_) return false;
    while (at_ == calls_.used_[chunk_]) {
        ++chunk_;
        at_ = 0;
    }
    const std::byte* p = calls_.chunks_[chunk_] + at_;
    std::uint8_t header[kHeaderBytes];
    p = get(p, header);
    c = HeldCall{};
    c.kind = static_cast<HeldCall::Kind>(header[0]);
    const std::uint8_t flags = header[3];
    int plane = plane_of(header[5]);
    if (header[5] == kPlaneWide) {
        std::int32_t wide = 0;
        p = get(p, wide);
        plane = wide;
    }
    switch (c.kind) {
        case HeldCall::Kind::kBegin:
            c.plane = plane;
            c.side = (flags & kSideNegative) != 0 ? -1 : 1;
            p = get(p, c.radius);
            break;
        case HeldCall::Kind::kEnd:
            break;
        case HeldCall::Kind::kWalls:
            c.on = (flags & kOn) != 0;
            break;
        case HeldCall::Kind::kProgrammed:
        case HeldCall::Kind::kExecuted: {
            PathSegment& s = c.segment;
            const std::size_t k = slot_of(c.kind);
            s.kind = static_cast<SegmentKind>(header[1]);
            s.role = static_cast<Role>(header[2]);
            s.ccw = (flags & kCcw) != 0;
            s.plane = plane;
            if ((flags & kSameBlock) != 0) {
                s.block = last_.block[k];
            } else if ((flags & kNextBlock) != 0) {
                s.block = BlockRef{last_.block[k].number + 1, last_.block[k].line + 1};
            } else if ((flags & kNextNumber) != 0) {
                s.block = BlockRef{last_.block[k].number + 1, last_.block[k].line};
            } else {
                p = get(p, s.block.number);
                p = get(p, s.block.line);
            }
            if ((flags & kStartIsLast) != 0)
                s.start = last_.end[k];
            else
                p = get_point(p, s.start);
            for (int i = 0; i < 3; ++i) {
                if ((header[4] & (1u << i)) != 0)
                    s.end[i] = s.start[i];
                else
                    p = get(p, s.end[i]);
            }
            if ((flags & kCentre) != 0) {
                for (int i = 0; i < 3; ++i) {
                    if ((header[4] & (8u << i)) != 0)
                        s.center[i] = s.start[i];
                    else
                        p = get(p, s.center[i]);
                }
            }
            if ((flags & kSweep) != 0)
                p = get(p, s.sweep);
            else if ((flags & kSweepZero) != 0)
                s.sweep = 0.0;
            else
                s.sweep = std::numeric_limits<double>::quiet_NaN();
            last_.end[k] = s.end;
            last_.block[k] = s.block;
            last_.has[k] = true;
            break;
        }
    }
    at_ = static_cast<std::size_t>(p - calls_.chunks_[chunk_]);
    ++read_;
    return true;
}

std::size_t HeldCalls::bytes() const noexcept {
    return std::accumulate(used_.begin(), used_.end(), std::size_t{0});
}

void HeldCalls::clear() noexcept {
    std::fill(used_.begin(), used_.end(), std::size_t{0});
    current_ = 0;
    count_ = 0;
    last_ = Last{};
}

void HeldCalls::swap(HeldCalls& other) noexcept {
    std::swap(chunk_bytes_, other.chunk_bytes_);
    chunks_.swap(other.chunks_);
    used_.swap(other.used_);
    ready_.swap(other.ready_);
    std::swap(current_, other.current_);
    std::swap(count_, other.count_);
    std::swap(last_, other.last_);
}

}  // namespace apci::run::detail
