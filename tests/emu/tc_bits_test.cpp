// SPDX-License-Identifier: MIT
// ERROR and STATUS bit constants ([APCI-TC] Tables 4 and 5) and their name lookups.
#include <gtest/gtest.h>

#include "objif/map/tc_bits.h"

namespace tc = objif::map::tc;

namespace {

TEST(TcBits, ErrorBitsHaveTheApciTcValues) {
    EXPECT_EQ(tc::kInitError, 0x01);
    EXPECT_EQ(tc::kKorrError, 0x02);
    EXPECT_EQ(tc::kCalcError, 0x04);
    EXPECT_EQ(tc::kPlaneError, 0x08);
    EXPECT_EQ(tc::kCenterError, 0x10);
    EXPECT_EQ(tc::kErrorMask, 0x1F);
}

TEST(TcBits, StatusBitsHaveTheApciTcValues) {
    EXPECT_EQ(tc::kRun, 1 << 0);
    EXPECT_EQ(tc::kProfMarked, 1 << 1);
}

TEST(TcBits, ErrorBitNamesAreTheApciTcNames) {
    EXPECT_EQ(tc::error_bit_name(tc::kInitError), "InitError");
    EXPECT_EQ(tc::error_bit_name(tc::kKorrError), "KorrError");
    EXPECT_EQ(tc::error_bit_name(tc::kCalcError), "CalcError");
    EXPECT_EQ(tc::error_bit_name(tc::kPlaneError), "PlaneError");
    EXPECT_EQ(tc::error_bit_name(tc::kCenterError), "CenterError");
    EXPECT_EQ(tc::error_bit_name(0x20), "");
    EXPECT_EQ(tc::error_bit_name(0x03), "") << "only single bits have a name";
}

TEST(TcBits, StatusBitNamesAreTheApciTcNames) {
    EXPECT_EQ(tc::status_bit_name(tc::kRun), "Run");
    EXPECT_EQ(tc::status_bit_name(tc::kProfMarked), "ProfMarked");
    EXPECT_EQ(tc::status_bit_name(0x04), "");
}

TEST(TcBits, NamesLookUpTheirBits) {
    std::int32_t mask = 0;
    for (const auto& b : tc::kErrorBits) {
        ASSERT_TRUE(tc::error_bit_from_name(b.name, mask)) << b.name;
        EXPECT_EQ(mask, b.mask);
    }
    ASSERT_TRUE(tc::status_bit_from_name("ProfMarked", mask));
    EXPECT_EQ(mask, tc::kProfMarked);
    mask = 77;
    EXPECT_FALSE(tc::error_bit_from_name("initerror", mask)) << "names are exact";
    EXPECT_FALSE(tc::status_bit_from_name("InitError", mask)) << "an ERROR name is not a STATUS bit";
    EXPECT_EQ(mask, 77) << "a failed lookup leaves the output alone";
}

TEST(TcBits, RegisterWordsDecodeByName) {
    EXPECT_EQ(tc::describe_error(0), "none");
    EXPECT_EQ(tc::describe_error(tc::kInitError | tc::kCalcError), "InitError|CalcError");
    EXPECT_EQ(tc::describe_error(0x1F), "InitError|KorrError|CalcError|PlaneError|CenterError");
    EXPECT_EQ(tc::describe_error(0x41), "InitError|unknown(0x40)");
    EXPECT_EQ(tc::describe_status(tc::kRun | tc::kProfMarked), "Run|ProfMarked");
    EXPECT_EQ(tc::describe_status(static_cast<std::int32_t>(0x80000000u)), "unknown(0x80000000)");
}

}  // namespace
