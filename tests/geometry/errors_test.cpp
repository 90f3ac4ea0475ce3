// SPDX-License-Identifier: MIT
// Error bits exactly as [APCI-TC] "Tabelle 4: Fehlerstatuswort Error des TC-Moduls", and the
// one reason table.
#include "rwmos/geometry/errors.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace rwmos::geom {
namespace {

TEST(ErrorBits, ValuesAreThoseOfTable4) {
    EXPECT_EQ(bits(ErrorBit::kInitError), 0x01u);
    EXPECT_EQ(bits(ErrorBit::kKorrError), 0x02u);
    EXPECT_EQ(bits(ErrorBit::kCalcError), 0x04u);
    EXPECT_EQ(bits(ErrorBit::kPlaneError), 0x08u);
    EXPECT_EQ(bits(ErrorBit::kCenterError), 0x10u);
}

TEST(ErrorBits, NamesAreTheApciTcNames) {
    EXPECT_EQ(error_bit_name(ErrorBit::kInitError), "InitError");
    EXPECT_EQ(error_bit_name(ErrorBit::kKorrError), "KorrError");
    EXPECT_EQ(error_bit_name(ErrorBit::kCalcError), "CalcError");
    EXPECT_EQ(error_bit_name(ErrorBit::kPlaneError), "PlaneError");
    EXPECT_EQ(error_bit_name(ErrorBit::kCenterError), "CenterError");
    EXPECT_EQ(error_bit_name(static_cast<ErrorBit>(0x20)), "Unknown");
}

TEST(ErrorBits, HasTestsOneBitOfASet) {
    const ErrorBits set = bits(ErrorBit::kKorrError) | bits(ErrorBit::kCenterError);
    EXPECT_TRUE(has(set, ErrorBit::kKorrError));
    EXPECT_TRUE(has(set, ErrorBit::kCenterError));
    EXPECT_FALSE(has(set, ErrorBit::kCalcError));
}

TEST(Reasons, EveryFailureMapsToExactlyOneBitWithANameAndMessage) {
    std::set<std::string> names;
    for (std::size_t i = 1; i < kReasonCount; ++i) {
        const auto reason = static_cast<Reason>(i);
        const ErrorBits b = reason_bits(reason);
        EXPECT_NE(b, 0u) << i;
        EXPECT_EQ(b & (b - 1), 0u) << "more than one bit for reason " << i;
        EXPECT_NE(reason_name(reason), "Unknown");
        EXPECT_FALSE(reason_message(reason).empty());
        names.insert(std::string(reason_name(reason)));
    }
    EXPECT_EQ(names.size(), kReasonCount - 1);
    EXPECT_EQ(reason_bits(Reason::kNone), 0u);
}

TEST(Reasons, GeometryFailuresMapToTheirTable4Bits) {
    EXPECT_EQ(reason_bits(Reason::kOffsetRadiusNotPositive), bits(ErrorBit::kCalcError));
    EXPECT_EQ(reason_bits(Reason::kArcRadiiDiffer), bits(ErrorBit::kCenterError));
    EXPECT_EQ(reason_bits(Reason::kHeldElementTooShort), bits(ErrorBit::kKorrError));
    EXPECT_EQ(reason_bits(Reason::kNextElementTooShort), bits(ErrorBit::kKorrError));
    EXPECT_EQ(reason_bits(Reason::kNoCornerSolution), bits(ErrorBit::kKorrError));
    EXPECT_EQ(reason_bits(Reason::kNotStarted), bits(ErrorBit::kInitError));
}

TEST(Reasons, UnknownReasonValueIsNamedUnknown) {
    EXPECT_EQ(reason_name(static_cast<Reason>(200)), "Unknown");
    EXPECT_EQ(reason_message(static_cast<Reason>(200)), "unknown reason");
}

}  // namespace
}  // namespace rwmos::geom
