// SPDX-License-Identifier: MIT
// Little-endian integers, whatever the host's byte order: the wire frame (docs/wire-frame.md),
// the dual-port RAM's words (docs/dpram.md) and the bytes the host tools lay out are
// little-endian on every machine. On a little-endian host these are no-ops; on a big-endian
// one (s390x, big-endian PowerPC, MIPS) they swap the bytes. Tested on s390x under QEMU
// (scripts/ci/big-endian.sh).
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace objif {

static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big,
              "mixed-endian hosts are not supported");

// The value with its bytes in reverse order.
template <class T>
constexpr T byteswap(T v) noexcept {
    static_assert(std::is_integral_v<T> && std::is_unsigned_v<T>);
    if constexpr (sizeof(T) == 1) {
        return v;
    } else if constexpr (sizeof(T) == 2) {
        return static_cast<T>(__builtin_bswap16(v));
    } else if constexpr (sizeof(T) == 4) {
        return static_cast<T>(__builtin_bswap32(v));
    } else {
        static_assert(sizeof(T) == 8);
        return static_cast<T>(__builtin_bswap64(v));
    }
}

// A value as it is stored little-endian (and back: the same swap).
template <class T>
constexpr T to_little(T v) noexcept {
    if constexpr (std::endian::native == std::endian::big) {
        return byteswap(v);
    } else {
        return v;
    }
}
template <class T>
constexpr T from_little(T v) noexcept {
    return to_little(v);
}

// Loads and stores of little-endian unsigned integers at any alignment.
template <class T>
T load_little(const void* p) noexcept {
    T v;
    std::memcpy(&v, p, sizeof v);
    return from_little(v);
}
template <class T>
void store_little(void* p, T v) noexcept {
    v = to_little(v);
    std::memcpy(p, &v, sizeof v);
}

}  // namespace objif
