// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <set>

#include "objif/status.h"

using objif::Status;

TEST(StatusTable, EveryCodeHasANameAndMessageAndRoundTrips) {
    const Status all[] = {
        Status::kOk,           Status::kNoSuchDevice,    Status::kObjectMissing,
        Status::kSubMissing,   Status::kStaleHandle,     Status::kHandleMismatch,
        Status::kReadOnly,     Status::kWriteOnly,       Status::kTypeMismatch,
        Status::kValueTooHigh, Status::kValueTooLow,     Status::kInvalidValue,
        Status::kWrongDeviceState, Status::kBusy,        Status::kMotionClaimed,
        Status::kGeneralError,
        Status::kBadFrame,     Status::kUnknownOpcode,   Status::kTransportError,
        Status::kTimeout,      Status::kNotSupported,    Status::kInvalidArgument,
        Status::kNoMemory};
    static_assert(std::size(all) == objif::kStatusCount);
    std::set<std::string_view> names;
    for (Status s : all) {
        EXPECT_NE(objif::status_name(s), "Unknown");
        EXPECT_FALSE(objif::status_message(s).empty());
        names.insert(objif::status_name(s));
        Status back{};
        ASSERT_TRUE(objif::status_from_code(objif::status_code(s), back));
        EXPECT_EQ(back, s);
    }
    EXPECT_EQ(names.size(), objif::kStatusCount);
}

TEST(StatusTable, CanOpenCodesAreTheStandardAbortCodes) {
    EXPECT_EQ(objif::status_code(Status::kObjectMissing), 0x06020000u);
    EXPECT_EQ(objif::status_code(Status::kSubMissing), 0x06090011u);
    EXPECT_EQ(objif::status_code(Status::kReadOnly), 0x06010002u);
    EXPECT_EQ(objif::status_code(Status::kWriteOnly), 0x06010001u);
    EXPECT_EQ(objif::status_code(Status::kTypeMismatch), 0x06070010u);
    EXPECT_EQ(objif::status_code(Status::kValueTooHigh), 0x06090031u);
    EXPECT_EQ(objif::status_code(Status::kValueTooLow), 0x06090032u);
    EXPECT_EQ(objif::status_code(Status::kWrongDeviceState), 0x08000022u);
}

TEST(StatusTable, UnknownCodeIsRefused) {
    Status s{};
    EXPECT_FALSE(objif::status_from_code(0xDEADBEEF, s));
    EXPECT_EQ(objif::status_name(static_cast<Status>(0xDEADBEEF)), "Unknown");
}
