// SPDX-License-Identifier: MIT
// Board module (bus 1000): every object read, written, refused.
#include <gtest/gtest.h>

#include "rwmos/board.h"
#include "rwmos/board_state.h"
#include "rwmos/object_map.h"

using objif::Descriptor;
using objif::Status;
using objif::Value;
using objif::ValueType;

namespace {

Descriptor board_object(std::int32_t index, std::int32_t sub = 0) {
    return Descriptor{{rwmos::board::kBus, rwmos::board::kDevice, index, sub}, objif::kNoHandle};
}

TEST(BoardModule, FirmwareVersionReadsThroughTheDictionary) {
    rwmos::Board board;
    auto d = board_object(rwmos::board::kIdxFirmwareVersion);
    Value v;
    ASSERT_EQ(board.read(d, ValueType::kInt32, v), Status::kOk);
    EXPECT_EQ(v, Value::of_int(rwmos::kFirmwareVersion));
}

TEST(BoardModule, RsZeroesTheTcRotation) {
    rwmos::Board board;
    auto angle = Descriptor{{1300, 0, 20, 0}, 0};
    ASSERT_EQ(board.write(angle, Value::of_double(30.0)), Status::kOk);
    auto rs = board_object(rwmos::board::kIdxRs);
    ASSERT_EQ(board.write(rs, Value::of_int(0)), Status::kOk);
    Value v;
    ASSERT_EQ(board.read(angle, ValueType::kDouble, v), Status::kOk);
    EXPECT_EQ(v, Value::of_double(0.0));
}

}  // namespace
