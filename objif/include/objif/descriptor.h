// SPDX-License-Identifier: MIT
// The object descriptor of the universal object interface: (BusNumber,
// DeviceNumber, Index, SubIndex) plus the handle the firmware issues on first
// access. The handle is cached in the descriptor; after TC Clean it is stale
// and the board refuses it ([APCI-TC], Table 2 "Clean": PCAP programs must zero
// their handles).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace objif {

struct Address {
    std::int32_t bus = 0;
    std::int32_t device = 0;
    std::int32_t index = 0;
    std::int32_t subindex = 0;
    friend constexpr bool operator==(const Address&, const Address&) = default;
    std::string to_string() const;  // "1300/1/1/8"
};

// A hash of an address, for maps keyed by it (the dictionary's handle slots, the names).
struct AddressHash {
    std::size_t operator()(const Address& a) const noexcept;
};

using Handle = std::uint32_t;  // 0 = not yet resolved
inline constexpr Handle kNoHandle = 0;

struct Descriptor {
    Address address;
    Handle handle = kNoHandle;
};

}  // namespace objif
