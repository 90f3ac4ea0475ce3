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

// apci::object() names the object and leaves the handle at 0, "not yet resolved" (apci.h): the
// first access resolves it, whichever board it is used on; a descriptor with a handle the board
// did not give is refused.
TEST(CppBoard, ObjectHelperLeavesTheHandleUnresolved) {
    constexpr auto fixed = apci::object(1300, 1, 2, 3);
    static_assert(fixed.bus == 1300 && fixed.device == 1 && fixed.index == 2 &&
                  fixed.subindex == 3 && fixed.handle == 0);
    auto radius = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_RADIUS);
    EXPECT_EQ(radius.handle, 0u);
    apci::Board board("emu:");
    ASSERT_TRUE(board) << board.last_error();
    const auto first = board.read_double(radius);
    ASSERT_EQ(first.status, APCI_OK) << board.last_error();
    EXPECT_NE(radius.handle, 0u) << "the first access fills in the handle";
    // Used again with its handle, and fresh on another board: both resolve.
    EXPECT_EQ(board.read_double(radius).status, APCI_OK) << board.last_error();
    apci::Board other("emu:");
    auto fresh = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_RADIUS);
    EXPECT_EQ(other.read_double(fresh).status, APCI_OK) << other.last_error();
    // A handle the board never gave is not taken for resolved.
    auto forged = apci::object(APCI_TC_BUS, 1, 1, APCI_TC_RADIUS);
    forged.handle = 0x7fff'fff0u;
    EXPECT_NE(board.read_double(forged).status, APCI_OK);
}

}  // namespace

extern "C" int c_api_round_trip(void);

TEST(CApiFromC, RoundTripCompiledAsC11Works) { EXPECT_EQ(c_api_round_trip(), 0); }
