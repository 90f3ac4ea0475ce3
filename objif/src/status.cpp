// SPDX-License-Identifier: MIT
#include "objif/status.h"

#include <array>

namespace objif {
namespace {

struct StatusRow {
    Status status;
    std::string_view name;
    std::string_view message;
};

// The one table. Keep in step with the enum: the static_assert below counts rows.
constexpr std::array kStatusTable{
    StatusRow{Status::kOk, "Ok", "success"},
    StatusRow{Status::kNoSuchDevice, "NoSuchDevice", "bus or device number does not exist on this board"},
    StatusRow{Status::kObjectMissing, "ObjectMissing", "object index does not exist"},
    StatusRow{Status::kSubMissing, "SubMissing", "subindex does not exist for this object"},
    StatusRow{Status::kStaleHandle, "StaleHandle", "object handle was discarded (TC Clean) or never issued; zero it"},
    StatusRow{Status::kHandleMismatch, "HandleMismatch", "object handle belongs to a different object"},
    StatusRow{Status::kReadOnly, "ReadOnly", "object is read-only"},
    StatusRow{Status::kWriteOnly, "WriteOnly", "object is write-only"},
    StatusRow{Status::kTypeMismatch, "TypeMismatch", "value type does not match the object (int vs double)"},
    StatusRow{Status::kValueTooHigh, "ValueTooHigh", "value above the object's range"},
    StatusRow{Status::kValueTooLow, "ValueTooLow", "value below the object's range"},
    StatusRow{Status::kInvalidValue, "InvalidValue", "value not allowed (NaN, infinity or not one of the permitted values)"},
    StatusRow{Status::kWrongDeviceState, "WrongDeviceState", "not possible in the present device state"},
    StatusRow{Status::kBusy, "Busy", "spooler full, nothing taken; try again"},
    StatusRow{Status::kMotionClaimed, "MotionClaimed", "another client holds the board's motion; nothing was done"},
    StatusRow{Status::kGeneralError, "GeneralError", "general error (the message says where)"},
    StatusRow{Status::kBadFrame, "BadFrame", "malformed wire frame"},
    StatusRow{Status::kUnknownOpcode, "UnknownOpcode", "frame opcode not served"},
    StatusRow{Status::kTransportError, "TransportError", "transport to the board failed"},
    StatusRow{Status::kTimeout, "Timeout", "board did not answer in time"},
    StatusRow{Status::kNotSupported, "NotSupported", "not supported by this device or transport"},
    StatusRow{Status::kInvalidArgument, "InvalidArgument", "invalid argument (a null pointer, a bad device URI or option)"},
    StatusRow{Status::kNoMemory, "NoMemory", "out of memory"},
};
static_assert(kStatusTable.size() == kStatusCount, "status table and enum out of step");

constexpr bool codes_unique() {
    for (std::size_t i = 0; i < kStatusTable.size(); ++i)
        for (std::size_t j = i + 1; j < kStatusTable.size(); ++j)
            if (kStatusTable[i].status == kStatusTable[j].status) return false;
    return true;
}
static_assert(codes_unique(), "two status rows share a code");

constexpr const StatusRow* find_row(Status s) {
    for (const auto& row : kStatusTable)
        if (row.status == s) return &row;
    return nullptr;
}

}  // namespace

std::string_view status_name(Status s) noexcept {
    const auto* row = find_row(s);
    return row ? row->name : std::string_view{"Unknown"};
}

std::string_view status_message(Status s) noexcept {
    const auto* row = find_row(s);
    return row ? row->message : std::string_view{"unknown status code"};
}

bool status_from_code(std::uint32_t code, Status& out) noexcept {
    const auto* row = find_row(static_cast<Status>(code));
    if (!row) return false;
    out = row->status;
    return true;
}

}  // namespace objif
