// SPDX-License-Identifier: MIT
// The seam between the executor and the modules that displace the axes from the interpolated
// path cycle by cycle (the OTC wear offsets, docs/otc.md; temperature compensation). The
// executor interpolates the nominal path (the spooled moves) and asks the module for the
// offsets of each evaluated cycle; the axes are at nominal + offsets.
//
// Virtual time stays cheap: while the offsets are a function of the move and its cycle k alone
// (per_cycle() false), the executor evaluates them once at the end of a stretch with at(), and
// must get the same bits as stepping every cycle with step(). While a ramp or another
// time-dependent state is under way (per_cycle() true) it steps every cycle.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "rwmos/motion/interpolator.h"
#include "rwmos/motion/types.h"

namespace rwmos::motion {

class CycleOffsets {
  public:
    virtual ~CycleOffsets() = default;

    // `m` starts now; `next` is the move queued behind it (nullptr if none yet).
    virtual void move_started(const Move& m, const Move* next) noexcept = 0;
    // `m` ended after k of its n cycles (k < n: interrupted by a direct command).
    virtual void move_finished(const Move& m, std::uint64_t k, std::uint64_t n) noexcept = 0;

    // True when the offsets from cycle k of n of `m` on (m == nullptr: standing still after
    // the last move) must be stepped cycle by cycle.
    virtual bool per_cycle(const Move* m, std::uint64_t k, std::uint64_t n) const noexcept = 0;
    // One cycle of `dt` seconds ran and left the nominal path at cycle k of n of `m` (m ==
    // nullptr: standing still): steps the time-dependent state, then adds the offsets to `pos`.
    virtual void step(const Move* m, std::uint64_t k, std::uint64_t n, double dt,
                      AxisVector& pos) noexcept = 0;
    // The offsets at cycle k of n of `m` without stepping (valid while !per_cycle), added to `pos`.
    virtual void at(const Move* m, std::uint64_t k, std::uint64_t n,
                    AxisVector& pos) const noexcept = 0;

    // True while the module, until its settings change, does nothing per move: move_started and
    // move_finished change nothing, per_cycle is false, and at() adds the same offsets for every
    // move and cycle and leaves the same state however often it is called. The executor then
    // evaluates at() once, after the last move of a stretch, instead of after every move.
    virtual bool inert() const noexcept { return false; }
};

// Several modules' offsets (OTC wear, temperature), added in order: each module sees the
// position with the offsets of those before it. Every module is told of every move and every
// cycle; the chain needs every cycle run when any of them does.
class CycleOffsetsChain final : public CycleOffsets {
  public:
    static constexpr std::size_t kMaxModules = 4;
    // Not owned; false when the chain is full.
    bool add(CycleOffsets* module) noexcept {
        if (count_ == kMaxModules) return false;
        modules_[count_++] = module;
        return true;
    }

    void move_started(const Move& m, const Move* next) noexcept override {
        for (std::size_t i = 0; i < count_; ++i) modules_[i]->move_started(m, next);
    }
    void move_finished(const Move& m, std::uint64_t k, std::uint64_t n) noexcept override {
        for (std::size_t i = 0; i < count_; ++i) modules_[i]->move_finished(m, k, n);
    }
    bool per_cycle(const Move* m, std::uint64_t k, std::uint64_t n) const noexcept override {
        bool any = false;
        for (std::size_t i = 0; i < count_; ++i) any = modules_[i]->per_cycle(m, k, n) || any;
        return any;
    }
    void step(const Move* m, std::uint64_t k, std::uint64_t n, double dt,
              AxisVector& pos) noexcept override {
        for (std::size_t i = 0; i < count_; ++i) modules_[i]->step(m, k, n, dt, pos);
    }
    void at(const Move* m, std::uint64_t k, std::uint64_t n,
            AxisVector& pos) const noexcept override {
        for (std::size_t i = 0; i < count_; ++i) modules_[i]->at(m, k, n, pos);
    }
    bool inert() const noexcept override {
        for (std::size_t i = 0; i < count_; ++i)
            if (!modules_[i]->inert()) return false;
        return true;
    }

  private:
    std::array<CycleOffsets*, kMaxModules> modules_{};
    std::size_t count_ = 0;
};

}  // namespace rwmos::motion
