// SPDX-License-Identifier: MIT
// The names of an enum's enumerators as one constexpr table, indexed by the enumerator's value:
//   constexpr auto kModes =
//       objif::enum_names<Mode::kCont, Mode::kAuto>({"CONT", "DISC", "AUTO"}, "?");
//   std::string_view mode_name(Mode m) noexcept { return kModes(m); }
// for an enum whose enumerators run without a gap from First to Last. The table must hold one
// name per enumerator (checked when it is built, at compile time); a value outside them (cast
// from an integer) is given the fallback. Header-only: the emulator, the host and objif use it.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>
#include <type_traits>

namespace objif {

template <typename E, std::size_t N>
class EnumNames {
    static_assert(std::is_enum_v<E>);

  public:
    constexpr EnumNames(E first, const std::string_view (&names)[N], std::string_view fallback)
        : first_(first), fallback_(fallback) {
        for (std::size_t i = 0; i < N; ++i) names_[i] = names[i];
    }

    constexpr std::string_view operator()(E value) const noexcept {
        const long long i = static_cast<long long>(value) - static_cast<long long>(first_);
        return i >= 0 && i < static_cast<long long>(N) ? names_[static_cast<std::size_t>(i)]
                                                       : fallback_;
    }

  private:
    E first_;
    std::array<std::string_view, N> names_{};
    std::string_view fallback_;
};

// The table of the enumerators First..Last (of one enum, without a gap), `names` in their order.
template <auto First, auto Last, std::size_t N>
consteval EnumNames<decltype(First), N> enum_names(const std::string_view (&names)[N],
                                                   std::string_view fallback) {
    static_assert(std::is_same_v<decltype(First), decltype(Last)>, "First and Last of one enum");
    static_assert(static_cast<long long>(Last) - static_cast<long long>(First) + 1 ==
                      static_cast<long long>(N),
                  "one name for each enumerator from First to Last");
    return EnumNames<decltype(First), N>(First, names, fallback);
}

}  // namespace objif
