// SPDX-License-Identifier: MIT
// Deterministic random numbers for the property tests (splitmix64): every run draws the same
// sequence from the same seed, on every machine.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace apci::test {

class Rng {
  public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    double log_uniform(double lo, double hi) {
        return std::exp(uniform(std::log(lo), std::log(hi)));
    }
    bool chance(double p) { return uniform() < p; }
    int integer(int lo, int hi) { return lo + static_cast<int>(next() % (hi - lo + 1)); }
    double sign() { return chance(0.5) ? 1.0 : -1.0; }
    template <typename T, std::size_t N>
    const T& pick(const T (&items)[N]) {
        return items[next() % N];
    }

  private:
    std::uint64_t state_;
};

}  // namespace apci::test
