// SPDX-License-Identifier: MIT
// The calls the self-approach check's hold keeps back (self_approach.cpp), written compactly one
// after the other in chunks allocated once each and read back once, in order, exactly as given
// (docs/performance.md "Held calls written compactly").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "apci/run/path.h"
#include "ready_pages.h"

namespace apci::run::detail {

// One call the check was given, as the hold gives it back.
struct HeldCall {
    enum class Kind : std::uint8_t { kBegin, kEnd, kProgrammed, kExecuted, kWalls };
    Kind kind = Kind::kBegin;
    // kProgrammed, kExecuted: the fields of the segment the check reads (block, kind, role,
    // start, end, center, ccw, plane, sweep), bit for bit; the others as a new PathSegment has
    // them.
    PathSegment segment;
    double radius = 0.0;  // kBegin
    int plane = 17;       // kBegin
    int side = 1;         // kBegin: -1 or 1
    bool on = false;      // kWalls
};

// The calls in the order given. A record takes a few bytes of header and only the numbers that
// are not found from the record of its kind before it: an executed segment starts where the
// one before it ended, a programmed element where the element before it ended, a segment's
// block is that of the last of its kind or the one after it (the check is given the programmed
// elements ahead of the executed ones, so the two kinds interleave), a line in its plane keeps
// the third coordinate, a line has no centre and an element no sweep. A compare is of the bits (-0
// and 0 apart, a NaN's payload kept), so that what is read back is what was written. Chunks are
// kept when cleared.
class HeldCalls {
  public:
    static constexpr std::size_t kChunkBytes = kHugePage;  // a huge page's size (ready_pages.h)

    HeldCalls() = default;
    // Chunks of chunk_bytes, each mapped on its own.
    explicit HeldCalls(std::size_t chunk_bytes);
    // Chunks of Slab::kMostTaken carved from `memory` (made ready as carved), which must outlive
    // the calls written (a holder's memory shared with its other arrays: fewer blocks
    // taken in part).
    explicit HeldCalls(Slab& memory);

    void begin(double radius, int plane, int side);
    void end();
    void walls(bool on);
    // kind: kProgrammed or kExecuted.
    void segment(HeldCall::Kind kind, const PathSegment& s);

    std::size_t size() const noexcept { return count_; }
    bool empty() const noexcept { return count_ == 0; }
    // Bytes the records take (written so far).
    std::size_t bytes() const noexcept;
    // Empties it; its chunks stay for the next calls.
    void clear() noexcept;
    void swap(HeldCalls& other) noexcept;

    // Gives each call in order to f(const HeldCall&).
    template <class F>
    void for_each(F&& f) const {
        Reader r(*this);
        HeldCall c;
        while (r.next(c)) f(static_cast<const HeldCall&>(c));
    }

  private:
    // The most bytes one record takes.
    static constexpr std::size_t kMostRecord = 128;
    // What a record is written against (and read against): the end and the block of the last
    // programmed segment ([0]) and of the last executed one ([1]).
    struct Last {
        std::array<Point, 2> end{Point::Zero(), Point::Zero()};
        std::array<BlockRef, 2> block{};
        std::array<bool, 2> has{false, false};
    };
    class Reader {
      public:
        explicit Reader(const HeldCalls& calls) : calls_(calls) {}
        bool next(HeldCall& c);

      private:
        const HeldCalls& calls_;
        std::size_t chunk_ = 0, at_ = 0, read_ = 0;
        Last last_;
    };

    std::byte* room();  // where the next record goes (at least kMostRecord bytes)
    void wrote(std::byte* end);

    std::size_t chunk_bytes_ = kChunkBytes;
    Chunks chunks_;                  // mapped, or carved from a slab (ready_pages.h)
    std::vector<std::size_t> used_;  // bytes written in each chunk in use
    // Each mapped chunk's pages made ready ahead of the writer (ready_pages.h; kept when
    // cleared). A slab's chunks are ready when carved.
    std::vector<ReadyAhead> ready_;
    std::size_t current_ = 0;  // the chunk written to (when count_ > 0)
    std::size_t count_ = 0;
    Last last_;
};

}  // namespace apci::run::detail
