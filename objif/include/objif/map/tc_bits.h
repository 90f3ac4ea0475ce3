// SPDX-License-Identifier: MIT
// Bits of the TC module's registers, next to their register, with name
// lookups so tools can decode ERROR and STATUS by name (header-only).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace objif::map::tc {

// Names and meanings are string literals, so .data() is NUL-terminated (the C API relies on it).
struct BitName {
    std::int32_t mask;
    std::string_view name;     // [APCI-TC]'s name
    std::string_view meaning;  // one line of English
};

// ---- ERROR register: DeviceNumber 1, SubIndex 1 ([APCI-TC] Table 4).
// Set by the firmware, cleared only by writing ERROR (or RESET / Clean).
inline constexpr std::int32_t kInitError = 0x01;
inline constexpr std::int32_t kKorrError = 0x02;
inline constexpr std::int32_t kCalcError = 0x04;
inline constexpr std::int32_t kPlaneError = 0x08;
inline constexpr std::int32_t kCenterError = 0x10;
inline constexpr std::int32_t kErrorMask = 0x1F;

inline constexpr std::array<BitName, 5> kErrorBits{{
    {kInitError, "InitError", "initialisation error"},
    {kKorrError, "KorrError", "radius compensation not possible"},
    {kCalcError, "CalcError", "calculation error: operation not allowed or not executable"},
    {kPlaneError, "PlaneError", "operation in the wrong main plane"},
    {kCenterError, "CenterError", "arc centre wrong: start and end radius differ"},
}};

// ---- STATUS register: DeviceNumber 1, SubIndex 3 ([APCI-TC] Table 5).
inline constexpr std::int32_t kRun = 0x01;         // bit 0: compensation active
inline constexpr std::int32_t kProfMarked = 0x02;  // bit 1: a profile waits in the buffer
inline constexpr std::int32_t kStatusMask = 0x03;

inline constexpr std::array<BitName, 2> kStatusBits{{
    {kRun, "Run", "tool radius compensation active"},
    {kProfMarked, "ProfMarked", "a profile to be compensated waits in the buffer"},
}};

namespace detail {
template <std::size_t N>
constexpr std::string_view bit_name(const std::array<BitName, N>& bits, std::int32_t mask) noexcept {
    for (const auto& b : bits)
        if (b.mask == mask) return b.name;
    return {};
}
template <std::size_t N>
constexpr bool bit_from_name(const std::array<BitName, N>& bits, std::string_view name,
                             std::int32_t& mask) noexcept {
    for (const auto& b : bits)
        if (b.name == name) {
            mask = b.mask;
            return true;
        }
    return false;
}
template <std::size_t N>
std::string describe(const std::array<BitName, N>& bits, std::int32_t word, std::int32_t known) {
    if (word == 0) return "none";
    std::string out;
    for (const auto& b : bits)
        if ((word & b.mask) != 0) {
            if (!out.empty()) out += '|';
            out += b.name;
        }
    if ((word & ~known) != 0) {
        if (!out.empty()) out += '|';
        char buf[16];
        static constexpr char kHex[] = "0123456789abcdef";
        auto rest = static_cast<std::uint32_t>(word & ~known);
        int n = 0;
        do {
            buf[n++] = kHex[rest & 0xF];
            rest >>= 4;
        } while (rest != 0);
        out += "unknown(0x";
        while (n > 0) out += buf[--n];
        out += ')';
    }
    return out;
}
}  // namespace detail

// "InitError" for 0x01; empty for a mask that is not exactly one known bit.
constexpr std::string_view error_bit_name(std::int32_t mask) noexcept {
    return detail::bit_name(kErrorBits, mask);
}
constexpr std::string_view status_bit_name(std::int32_t mask) noexcept {
    return detail::bit_name(kStatusBits, mask);
}
// "CalcError" -> 0x04; false for an unknown name (exact, case-sensitive).
constexpr bool error_bit_from_name(std::string_view name, std::int32_t& mask) noexcept {
    return detail::bit_from_name(kErrorBits, name, mask);
}
constexpr bool status_bit_from_name(std::string_view name, std::int32_t& mask) noexcept {
    return detail::bit_from_name(kStatusBits, name, mask);
}
// A whole register word by name: "none", "InitError|CalcError",
// "Run|unknown(0x80)" for bits [APCI-TC] does not define.
inline std::string describe_error(std::int32_t word) {
    return detail::describe(kErrorBits, word, kErrorMask);
}
inline std::string describe_status(std::int32_t word) {
    return detail::describe(kStatusBits, word, kStatusMask);
}

}  // namespace objif::map::tc
