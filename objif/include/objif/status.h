// SPDX-License-Identifier: MIT
// One status enum, each value naming its 32-bit code, and one table (status.cpp)
// that maps code -> name -> message. CANopen SDO abort codes where one fits;
// the 0x0F00'xxxx range is ours (transport and board-specific conditions).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace objif {

enum class Status : std::uint32_t {
    kOk = 0x0000'0000,
    // Addressing, checked in this order: bus/device, index, subindex.
    kNoSuchDevice = 0x0602'0001,   // bus or device number not present (or option absent)
    kObjectMissing = 0x0602'0000,  // CANopen: object does not exist in the dictionary
    kSubMissing = 0x0609'0011,     // CANopen: subindex does not exist
    kStaleHandle = 0x0F00'0001,    // handle discarded (TC Clean) or never issued
    kHandleMismatch = 0x0F00'0002, // handle is live but names another object
    // Access.
    kReadOnly = 0x0601'0002,   // CANopen: attempt to write a read-only object
    kWriteOnly = 0x0601'0001,  // CANopen: attempt to read a write-only object
    // Type and range.
    kTypeMismatch = 0x0607'0010,  // CANopen: data type does not match
    kValueTooHigh = 0x0609'0031,  // CANopen: value of parameter written too high
    kValueTooLow = 0x0609'0032,   // CANopen: value of parameter written too low
    kInvalidValue = 0x0609'0030,  // CANopen: invalid value (NaN, infinity, not in set)
    // State.
    kWrongDeviceState = 0x0800'0022,  // CANopen: not possible in present device state
    kBusy = 0x0F00'0010,              // spooler full: nothing was taken, try again
    kMotionClaimed = 0x0F00'0011,     // another client holds the board's motion (docs/motion-claim.md)
    kGeneralError = 0x0800'0000,      // CANopen: general error
    // Frames and transports.
    kBadFrame = 0x0F00'0100,       // malformed wire frame (reason given separately)
    kUnknownOpcode = 0x0F00'0101,  // well-formed frame with an opcode we do not serve
    kTransportError = 0x0F00'0200, // the link to the board failed (I/O error, closed)
    kTimeout = 0x0504'0000,        // CANopen: SDO protocol timed out
    kNotSupported = 0x0F00'0300,   // the device or transport cannot do this
    kInvalidArgument = 0x0F00'0301,// bad argument from the caller (null pointer, bad URI)
    kNoMemory = 0x0F00'0302,       // allocation failed
};

// Number of Status values; status.cpp static_asserts its table against it.
inline constexpr std::size_t kStatusCount = 23;

// "kObjectMissing" -> "ObjectMissing"; unknown codes give "Unknown".
std::string_view status_name(Status s) noexcept;
// One line of English for a user.
std::string_view status_message(Status s) noexcept;
// Known code -> true and the enum; unknown -> false.
bool status_from_code(std::uint32_t code, Status& out) noexcept;

constexpr std::uint32_t status_code(Status s) noexcept { return static_cast<std::uint32_t>(s); }
constexpr bool ok(Status s) noexcept { return s == Status::kOk; }

}  // namespace objif
