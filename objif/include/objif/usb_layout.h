// SPDX-License-Identifier: MIT
// The USB face of a board (docs/design.md section 6, design): one vendor-specific
// interface with one bulk OUT and one bulk IN endpoint carrying the wire
// frames of frame.h, one request frame out, its reply frame in. docs/usb.md
// is the spec page.
//
// ADDI-DATA's USB vendor IDs are public; product IDs of USB boards are not,
// so the driver matches any product of these vendors whose interface has the
// layout below, and a device URI option (usb:?pid=0xNNNN) or the
// environment ($APCI_USB_PRODUCT_IDS="0xNNNN,0xMMMM") narrows the match.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "objif/frame.h"

namespace objif::usb {

inline constexpr std::array<std::uint16_t, 2> kVendorIds{
    0x15B8,  // ADDI-DATA GmbH
    0x10E8,  // the older ID used on ADDI-DATA boards (AMCC/ADDI-DATA)
};

inline constexpr std::uint8_t kInterfaceClass = 0xFF;  // vendor specific
inline constexpr std::uint8_t kInterfaceNumber = 0;
inline constexpr std::uint8_t kEndpointOut = 0x01;  // bulk, host -> board: request frames
inline constexpr std::uint8_t kEndpointIn = 0x81;   // bulk, board -> host: reply frames

// A frame may span several bulk transfers; the receiver reassembles it from
// the header's payload length (no zero-length packet needed). One transfer
// carries at most this many bytes.
inline constexpr std::size_t kMaxTransfer = kFrameOverhead + kMaxPayload;

// The product ID the emulated USB board reports (tests, umockdev); not an
// ADDI-DATA number.
inline constexpr std::uint16_t kEmulatorProductId = 0x8001;

}  // namespace objif::usb
