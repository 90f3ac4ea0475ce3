// SPDX-License-Identifier: MIT
// The header-only C++ API (apci.hpp): RAII board, typed results.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <utility>

#include "apci/apci.hpp"

namespace {

static_assert(!std::is_copy_constructible_v<apci::Board>, "a board has one owner");
static_assert(std::is_nothrow_move_constructible_v<apci::Board>);

TEST(CppBoard, OpensTheEmbeddedEmulatorByUri) {
    apci::Board board("emu:");
    ASSERT_TRUE(board.is_open()) << board.last_error();
    EXPECT_EQ(board.open_status(), APCI_OK);
    EXPECT_NE(board.native_handle(), nullptr);
}

TEST(CppBoard, FailedOpenKeepsStatusAndReason) {
    apci::Board board("shm:/nonexistent/apci");
    EXPECT_FALSE(board);
    EXPECT_EQ(board.open_status(), APCI_TRANSPORT_ERROR);
    EXPECT_NE(board.last_error().find("open /nonexistent/apci"), std::string_view::npos);
    auto o = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_STATUS);
    EXPECT_EQ(board.read_int(o).status, APCI_INVALID_ARGUMENT);
}

TEST(CppBoard, DefaultBoardIsClosedAndRefusesAccess) {
    apci::Board board;
    EXPECT_FALSE(board.is_open());
    EXPECT_EQ(board.last_error(), "board not open");
    auto o = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_RADIUS);
    EXPECT_EQ(board.write(o, 1.0).status, APCI_INVALID_ARGUMENT);
}

TEST(CppBoard, ResultCarriesStatusAndValue) {
    apci::Board board("emu:");
    auto radius = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_RADIUS);
    ASSERT_TRUE(board.write(radius, 2.5)) << board.last_error();
    const auto r = board.read_double(radius);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.value, 2.5);
    EXPECT_EQ(r.name(), "Ok");
    const auto wrong = board.read_int(radius);
    EXPECT_FALSE(wrong);
    EXPECT_EQ(wrong.status, APCI_TYPE_MISMATCH);
    EXPECT_EQ(wrong.name(), "TypeMismatch");
    EXPECT_EQ(wrong.value_or(-7), -7);
    EXPECT_NE(board.last_error().find("1300/1/1/7"), std::string_view::npos);
}

TEST(CppBoard, WriteOverloadTakesItsTypeFromTheArgument) {
    apci::Board board("emu:");
    auto wkzindex = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_WKZINDEX);
    auto radius = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_RADIUS);
    EXPECT_TRUE(board.write(wkzindex, 3));        // int
    EXPECT_TRUE(board.write(radius, 1.5));        // double
    EXPECT_EQ(board.write(wkzindex, 3.0).status, APCI_TYPE_MISMATCH);
    EXPECT_EQ(board.write(radius, 2).status, APCI_TYPE_MISMATCH);
    EXPECT_EQ(board.read<std::int32_t>(wkzindex).value, 3);
    EXPECT_EQ(board.read<double>(radius).value, 1.5);
}

TEST(CppBoard, MoveTransfersTheOpenBoard) {
    apci::Board a("emu:");
    auto wkzindex = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_WKZINDEX);
    ASSERT_TRUE(a.write(wkzindex, 9));
    apci::Board b(std::move(a));
    EXPECT_FALSE(a.is_open());  // NOLINT(bugprone-use-after-move,clang-analyzer-cplusplus.Move): moved-from state is documented
    ASSERT_TRUE(b.is_open());
    EXPECT_EQ(b.read_int(wkzindex).value, 9);  // same board, same handle
    apci::Board c;
    c = std::move(b);
    EXPECT_EQ(c.read_int(wkzindex).value, 9);
}

TEST(CppBoard, ObjectHelperLeavesTheHandleUnresolved) {
    constexpr auto o = apci::object(1300, 1, 2, 3);
    static_assert(o.bus == 1300 && o.device == 1 && o.index == 2 && o.subindex == 3 && o.handle == 0);
    SUCCEED();
}

}  // namespace

extern "C" int c_api_round_trip(void);

TEST(CApiFromC, RoundTripCompiledAsC11Works) { EXPECT_EQ(c_api_round_trip(), 0); }
