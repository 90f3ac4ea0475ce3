// SPDX-License-Identifier: MIT
// The C API of apci.h against the embedded emulator: opening, typed access,
// status mapping, last-error text, bad input, handles and TC Clean.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "apci/apci.h"
#include "objif/status.h"

namespace {

apci_object_descriptor tc_group(int32_t group, int32_t sub) {
    return {APCI_TC_BUS, APCI_TC_DEVICE_GROUP, group, sub, 0};
}

class Board : public ::testing::Test {
protected:
    void SetUp() override { ASSERT_EQ(apci_open("emu:", &board_), APCI_OK) << apci_last_error(nullptr); }
    void TearDown() override { apci_close(board_); }
    std::string last_error() const { return apci_last_error(board_); }
    apci_board* board_ = nullptr;
};

// ---- opening

TEST(Open, NullEmptyAndEmuAreTheEmbeddedEmulator) {
    for (const char* uri : {static_cast<const char*>(nullptr), "", "emu:"}) {
        apci_board* board = nullptr;
        ASSERT_EQ(apci_open(uri, &board), APCI_OK) << (uri ? uri : "NULL");
        ASSERT_NE(board, nullptr);
        auto radius = tc_group(1, APCI_TC_RADIUS);
        double r = -1.0;
        EXPECT_EQ(apci_read_double(board, &radius, &r), APCI_OK) << apci_last_error(board);
        apci_close(board);
    }
}

TEST(Open, EachOpenIsAFreshBoard) {
    apci_board* a = nullptr;
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open("emu:", &a), APCI_OK);
    ASSERT_EQ(apci_open("emu:", &b), APCI_OK);
    auto index_a = tc_group(1, APCI_TC_WKZINDEX);
    auto index_b = tc_group(1, APCI_TC_WKZINDEX);
    ASSERT_EQ(apci_write_int(a, &index_a, 17), APCI_OK) << apci_last_error(a);
    int32_t v = -1;
    ASSERT_EQ(apci_read_int(b, &index_b, &v), APCI_OK) << apci_last_error(b);
    EXPECT_NE(v, 17);
    ASSERT_EQ(apci_read_int(a, &index_a, &v), APCI_OK);
    EXPECT_EQ(v, 17);
    apci_close(a);
    apci_close(b);
}

TEST(Open, NoOptionTcRemovesTheTcModule) {
    apci_board* board = nullptr;
    ASSERT_EQ(apci_open("emu:?no-option-tc", &board), APCI_OK) << apci_last_error(nullptr);
    auto plane = apci_object_descriptor{APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_PLANE, 0, 0};
    int32_t v = 0;
    EXPECT_EQ(apci_read_int(board, &plane, &v), APCI_NO_SUCH_DEVICE);
    auto radius = tc_group(1, APCI_TC_RADIUS);
    EXPECT_EQ(apci_write_double(board, &radius, 1.0), APCI_NO_SUCH_DEVICE);
    apci_close(board);
}

TEST(Open, LastEmuOptionWins) {
    apci_board* board = nullptr;
    ASSERT_EQ(apci_open("emu:?no-option-tc&option-tc", &board), APCI_OK);
    auto plane = apci_object_descriptor{APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_PLANE, 0, 0};
    int32_t v = 0;
    EXPECT_EQ(apci_read_int(board, &plane, &v), APCI_OK) << apci_last_error(board);
    EXPECT_EQ(v, 17);  // [APCI-TC] Table 2: TcPlane default 17 (X-Y)
    apci_close(board);
}

struct BadUri {
    const char* uri;
    apci_status status;
    const char* says;  // a piece of the last-error text
};

class OpenRefuses : public ::testing::TestWithParam<BadUri> {};

TEST_P(OpenRefuses, WithAClearStatusAndTextAndNullBoard) {
    const BadUri& p = GetParam();
    apci_board* board = reinterpret_cast<apci_board*>(0x1);  // must be overwritten with NULL
    EXPECT_EQ(apci_open(p.uri, &board), p.status) << p.uri;
    EXPECT_EQ(board, nullptr);
    const std::string text = apci_last_error(nullptr);
    EXPECT_NE(text.find(p.says), std::string::npos) << text;
    EXPECT_NE(text.find(apci_status_name(p.status)), std::string::npos) << text;
}

INSTANTIATE_TEST_SUITE_P(
    UnreachableAndMalformedUris, OpenRefuses,
    ::testing::Values(
        BadUri{"unix:/nonexistent/apci8001.sock", APCI_TRANSPORT_ERROR,
               "connect /nonexistent/apci8001.sock: No such file or directory"},
        BadUri{"shm:/nonexistent/apci", APCI_TRANSPORT_ERROR, "open /nonexistent/apci"},
        BadUri{"pci:0000:ff:1f.7", APCI_TRANSPORT_ERROR, "no PCI function 0000:ff:1f.7"},
        BadUri{"usb:9:99", APCI_TRANSPORT_ERROR, "no ADDI-DATA USB board at bus 9 address 99"},
        BadUri{"unix:", APCI_INVALID_ARGUMENT, "needs the daemon's socket path"},
        BadUri{"pci:3:0.0", APCI_INVALID_ARGUMENT, "pci:DOMAIN:BUS:DEV.FN"},
        BadUri{"usb:1", APCI_INVALID_ARGUMENT, "usb:BUS:ADDR"},
        BadUri{"tcp:host:1", APCI_INVALID_ARGUMENT, "unknown device URI scheme 'tcp:'"},
        BadUri{"emulator", APCI_INVALID_ARGUMENT, "has no scheme"},
        BadUri{":x", APCI_INVALID_ARGUMENT, "has no scheme"},
        BadUri{"EMU:", APCI_INVALID_ARGUMENT, "invalid character"},
        BadUri{"emu:?optionTC", APCI_INVALID_ARGUMENT, "unknown emu: option 'optionTC'"},
        BadUri{"emu:?", APCI_INVALID_ARGUMENT, "empty option"},
        BadUri{"emu:?no-option-tc&", APCI_INVALID_ARGUMENT, "empty option"},
        BadUri{"emu:board0", APCI_INVALID_ARGUMENT, "takes no target"}));

TEST(Open, NullOutIsInvalidArgument) {
    EXPECT_EQ(apci_open("emu:", nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_NE(std::string(apci_last_error(nullptr)).find("out pointer is NULL"), std::string::npos);
}

TEST(Open, SuccessClearsTheThreadsOpenError) {
    apci_board* board = nullptr;
    ASSERT_NE(apci_open("usb:", &board), APCI_OK);
    ASSERT_STRNE(apci_last_error(nullptr), "");
    ASSERT_EQ(apci_open("emu:", &board), APCI_OK);
    EXPECT_STREQ(apci_last_error(nullptr), "");
    apci_close(board);
}

TEST(Open, OpenErrorTextIsPerThread) {
    apci_board* board = nullptr;
    ASSERT_EQ(apci_open("tcp:x", &board), APCI_INVALID_ARGUMENT);
    std::string other;
    std::thread([&] { other = apci_last_error(nullptr); }).join();
    EXPECT_EQ(other, "");
    EXPECT_NE(std::string(apci_last_error(nullptr)).find("tcp"), std::string::npos);
}

// NULL is accepted and ignored (apci.h): nothing is freed, and the thread's last error (here a
// failed open's) stays as it was.
TEST(Close, AcceptsNull) {
    apci_board* board = nullptr;
    ASSERT_EQ(apci_open("tcp:x", &board), APCI_INVALID_ARGUMENT);
    const std::string before = apci_last_error(nullptr);
    ASSERT_NE(before, "");
    apci_close(nullptr);
    EXPECT_EQ(apci_last_error(nullptr), before);
    // The library is still usable: the next open and close work.
    ASSERT_EQ(apci_open("emu:", &board), APCI_OK);
    apci_close(board);
}

// ---- typed access

TEST_F(Board, IntObjectRoundTrips) {
    auto wkzindex = tc_group(1, APCI_TC_WKZINDEX);
    ASSERT_EQ(apci_write_int(board_, &wkzindex, 1023), APCI_OK) << last_error();
    int32_t v = 0;
    ASSERT_EQ(apci_read_int(board_, &wkzindex, &v), APCI_OK) << last_error();
    EXPECT_EQ(v, 1023);
}

TEST_F(Board, DoubleObjectRoundTripsExactly) {
    auto radius = tc_group(2, APCI_TC_RADIUS);
    const double written = 0.1 + 0.2;  // not representable in few digits
    ASSERT_EQ(apci_write_double(board_, &radius, written), APCI_OK) << last_error();
    double v = 0;
    ASSERT_EQ(apci_read_double(board_, &radius, &v), APCI_OK) << last_error();
    EXPECT_EQ(v, written);
}

TEST_F(Board, WrongAccessorTypeIsTypeMismatchAndChangesNothing) {
    auto radius = tc_group(1, APCI_TC_RADIUS);
    ASSERT_EQ(apci_write_double(board_, &radius, 2.5), APCI_OK);
    EXPECT_EQ(apci_write_int(board_, &radius, 7), APCI_TYPE_MISMATCH);
    int32_t i = 0;
    EXPECT_EQ(apci_read_int(board_, &radius, &i), APCI_TYPE_MISMATCH);
    double d = 0;
    ASSERT_EQ(apci_read_double(board_, &radius, &d), APCI_OK);
    EXPECT_EQ(d, 2.5);

    auto wkzindex = tc_group(1, APCI_TC_WKZINDEX);
    EXPECT_EQ(apci_write_double(board_, &wkzindex, 3.0), APCI_TYPE_MISMATCH);
    EXPECT_EQ(apci_read_double(board_, &wkzindex, &d), APCI_TYPE_MISMATCH);
}

TEST_F(Board, NonFiniteDoubleIsInvalidValueAndChangesNothing) {
    auto radius = tc_group(1, APCI_TC_RADIUS);
    ASSERT_EQ(apci_write_double(board_, &radius, 1.25), APCI_OK);
    EXPECT_EQ(apci_write_double(board_, &radius, std::numeric_limits<double>::quiet_NaN()),
              APCI_INVALID_VALUE);
    EXPECT_EQ(apci_write_double(board_, &radius, std::numeric_limits<double>::infinity()),
              APCI_INVALID_VALUE);
    double d = 0;
    ASSERT_EQ(apci_read_double(board_, &radius, &d), APCI_OK);
    EXPECT_EQ(d, 1.25);
}

TEST_F(Board, OutOfRangeIntIsValueTooHighOrLow) {
    auto wkzindex = tc_group(1, APCI_TC_WKZINDEX);  // [APCI-TC] Table 3: 0..1023
    EXPECT_EQ(apci_write_int(board_, &wkzindex, 1024), APCI_VALUE_TOO_HIGH);
    EXPECT_EQ(apci_write_int(board_, &wkzindex, -1), APCI_VALUE_TOO_LOW);
}

TEST_F(Board, AccessRulesAreMapped) {
    auto left = tc_group(1, APCI_TC_LEFT);  // write-only
    int32_t v = 0;
    EXPECT_EQ(apci_read_int(board_, &left, &v), APCI_WRITE_ONLY);
    auto missing_index = tc_group(9, APCI_TC_STATUS);
    EXPECT_EQ(apci_read_int(board_, &missing_index, &v), APCI_OBJECT_MISSING);
    auto missing_sub = tc_group(1, 6);
    EXPECT_EQ(apci_read_int(board_, &missing_sub, &v), APCI_SUB_MISSING);
    apci_object_descriptor missing_bus{4711, 0, 0, 0, 0};
    EXPECT_EQ(apci_read_int(board_, &missing_bus, &v), APCI_NO_SUCH_DEVICE);
}

TEST_F(Board, FailedReadLeavesValueUntouched) {
    auto radius = tc_group(1, APCI_TC_RADIUS);
    int32_t v = 12345;
    ASSERT_NE(apci_read_int(board_, &radius, &v), APCI_OK);
    EXPECT_EQ(v, 12345);
}

// ---- bad input never crashes

TEST_F(Board, NullArgumentsAreInvalidArgumentWithText) {
    auto status = tc_group(1, APCI_TC_STATUS);
    int32_t i = 0;
    double d = 0;
    EXPECT_EQ(apci_read_int(nullptr, &status, &i), APCI_INVALID_ARGUMENT);
    EXPECT_NE(std::string(apci_last_error(nullptr)).find("apci_read_int: board is NULL"),
              std::string::npos);
    EXPECT_EQ(apci_write_double(nullptr, &status, 1.0), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_read_int(board_, nullptr, &i), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(last_error(), "apci_read_int: object descriptor is NULL");
    EXPECT_EQ(apci_read_double(board_, &status, nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(last_error(), "apci_read_double: value pointer is NULL");
    EXPECT_EQ(apci_read_int(board_, &status, nullptr), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_write_int(board_, nullptr, 1), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_write_double(board_, nullptr, 1.0), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(apci_read_double(board_, nullptr, &d), APCI_INVALID_ARGUMENT);
    EXPECT_EQ(status.handle, 0u);  // nothing was resolved
}

TEST_F(Board, GarbageDescriptorsAreRefusedNotCrashing) {
    int32_t v = 0;
    for (int32_t bus : {INT32_MIN, -1, 0, 1300, INT32_MAX})
        for (int32_t dev : {INT32_MIN, -1, 0, 1, 2, INT32_MAX})
            for (int32_t idx : {INT32_MIN, -1, 0, 1, 3, 4, INT32_MAX})
                for (int32_t sub : {INT32_MIN, -1, 0, 3, 13, INT32_MAX}) {
                    apci_object_descriptor o{bus, dev, idx, sub, 0};
                    const apci_status s = apci_read_int(board_, &o, &v);
                    EXPECT_STRNE(apci_status_name(s), "Unknown");
                    apci_object_descriptor forged{bus, dev, idx, sub, 0xDEADBEEFu};
                    EXPECT_NE(apci_write_int(board_, &forged, 0), APCI_OK);
                }
}

// ---- status codes

TEST(StatusCodes, EqualTheObjectInterfaceCodesWithTheSameNames) {
    const std::pair<apci_status, objif::Status> rows[] = {
        {APCI_OK, objif::Status::kOk},
        {APCI_NO_SUCH_DEVICE, objif::Status::kNoSuchDevice},
        {APCI_OBJECT_MISSING, objif::Status::kObjectMissing},
        {APCI_SUB_MISSING, objif::Status::kSubMissing},
        {APCI_STALE_HANDLE, objif::Status::kStaleHandle},
        {APCI_HANDLE_MISMATCH, objif::Status::kHandleMismatch},
        {APCI_READ_ONLY, objif::Status::kReadOnly},
        {APCI_WRITE_ONLY, objif::Status::kWriteOnly},
        {APCI_TYPE_MISMATCH, objif::Status::kTypeMismatch},
        {APCI_VALUE_TOO_HIGH, objif::Status::kValueTooHigh},
        {APCI_VALUE_TOO_LOW, objif::Status::kValueTooLow},
        {APCI_INVALID_VALUE, objif::Status::kInvalidValue},
        {APCI_WRONG_DEVICE_STATE, objif::Status::kWrongDeviceState},
        {APCI_BUSY, objif::Status::kBusy},
        {APCI_MOTION_CLAIMED, objif::Status::kMotionClaimed},
        {APCI_GENERAL_ERROR, objif::Status::kGeneralError},
        {APCI_BAD_FRAME, objif::Status::kBadFrame},
        {APCI_UNKNOWN_OPCODE, objif::Status::kUnknownOpcode},
        {APCI_TRANSPORT_ERROR, objif::Status::kTransportError},
        {APCI_TIMEOUT, objif::Status::kTimeout},
        {APCI_NOT_SUPPORTED, objif::Status::kNotSupported},
        {APCI_INVALID_ARGUMENT, objif::Status::kInvalidArgument},
        {APCI_NO_MEMORY, objif::Status::kNoMemory},
    };
    static_assert(std::size(rows) == APCI_STATUS_COUNT);
    for (const auto& [c, s] : rows) {
        EXPECT_EQ(c, objif::status_code(s));
        EXPECT_EQ(std::string(apci_status_name(c)), objif::status_name(s));
        EXPECT_EQ(std::string(apci_status_message(c)), objif::status_message(s));
    }
}

TEST(StatusCodes, UnknownCodeIsNamedUnknownNeverNull) {
    EXPECT_STREQ(apci_status_name(0x12345678u), "Unknown");
    ASSERT_NE(apci_status_message(0x12345678u), nullptr);
    EXPECT_STRNE(apci_status_message(0x12345678u), "");
}

TEST(Version, MatchesTheHeader) {
    EXPECT_EQ(std::string(apci_version()), std::to_string(APCI_VERSION_MAJOR) + "." +
                                               std::to_string(APCI_VERSION_MINOR) + "." +
                                               std::to_string(APCI_VERSION_PATCH));
}

TEST(TcBitNames, AreTheApciTcNames) {
    EXPECT_STREQ(apci_tc_error_bit_name(0), "InitError");
    EXPECT_STREQ(apci_tc_error_bit_name(1), "KorrError");
    EXPECT_STREQ(apci_tc_error_bit_name(2), "CalcError");
    EXPECT_STREQ(apci_tc_error_bit_name(3), "PlaneError");
    EXPECT_STREQ(apci_tc_error_bit_name(4), "CenterError");
    EXPECT_EQ(apci_tc_error_bit_name(5), nullptr);
    EXPECT_EQ(apci_tc_error_bit_name(-1), nullptr);
    EXPECT_STREQ(apci_tc_status_bit_name(0), "Run");
    EXPECT_STREQ(apci_tc_status_bit_name(1), "ProfMarked");
    EXPECT_EQ(apci_tc_status_bit_name(2), nullptr);
    EXPECT_EQ(apci_tc_status_bit_name(INT32_MIN), nullptr);
}

// ---- last error

TEST_F(Board, LastErrorNamesOperationObjectAndStatus) {
    auto missing = tc_group(9, APCI_TC_STATUS);
    int32_t v = 0;
    ASSERT_EQ(apci_read_int(board_, &missing, &v), APCI_OBJECT_MISSING);
    EXPECT_EQ(last_error(), "read int 1300/1/9/3: ObjectMissing (object index does not exist)");
    auto wkzindex = tc_group(1, APCI_TC_WKZINDEX);
    ASSERT_EQ(apci_write_int(board_, &wkzindex, 5000), APCI_VALUE_TOO_HIGH);
    EXPECT_EQ(last_error(), "write int 1300/1/1/8 = 5000: ValueTooHigh (value above the object's range)");
    auto radius = tc_group(1, APCI_TC_RADIUS);
    ASSERT_EQ(apci_write_int(board_, &radius, 2), APCI_TYPE_MISMATCH);
    EXPECT_EQ(last_error(), "write int 1300/1/1/7 = 2: TypeMismatch (value type does not match the "
                            "object (int vs double))");
}

TEST_F(Board, LastErrorNamesAStateRuleRefusal) {
    auto wkzindex = tc_group(1, APCI_TC_WKZINDEX);
    auto radius = tc_group(1, APCI_TC_RADIUS);
    auto left = tc_group(1, APCI_TC_LEFT);
    auto status = tc_group(1, APCI_TC_STATUS);
    auto x_axis = tc_group(1, APCI_TC_XAXIS);
    ASSERT_EQ(apci_write_int(board_, &wkzindex, 1), APCI_OK);
    ASSERT_EQ(apci_write_double(board_, &radius, 2.0), APCI_OK);
    ASSERT_EQ(apci_write_int(board_, &left, 1), APCI_OK);
    ASSERT_EQ(apci_write_int(board_, &status, 1), APCI_OK) << last_error();
    ASSERT_EQ(apci_write_int(board_, &x_axis, 2), APCI_WRONG_DEVICE_STATE);
    EXPECT_EQ(last_error(), "write int 1300/1/1/4 = 2: WrongDeviceState (not possible in the "
                            "present device state)");
}

TEST_F(Board, LastErrorIsEmptyAfterASuccessfulCall) {
    auto missing = tc_group(9, APCI_TC_STATUS);
    int32_t v = 0;
    ASSERT_NE(apci_read_int(board_, &missing, &v), APCI_OK);
    ASSERT_NE(last_error(), "");
    auto status = tc_group(1, APCI_TC_STATUS);
    ASSERT_EQ(apci_read_int(board_, &status, &v), APCI_OK);
    EXPECT_EQ(last_error(), "");
}

TEST_F(Board, LastErrorIsPerBoard) {
    apci_board* other = nullptr;
    ASSERT_EQ(apci_open("emu:", &other), APCI_OK);
    auto missing = tc_group(9, APCI_TC_STATUS);
    int32_t v = 0;
    ASSERT_NE(apci_read_int(board_, &missing, &v), APCI_OK);
    EXPECT_STREQ(apci_last_error(other), "");
    apci_close(other);
}

// ---- handles ([APCI-TC] Table 2 "Clean")

TEST_F(Board, HandleIsFilledOnFirstAccessAndReused) {
    auto status = tc_group(1, APCI_TC_STATUS);
    int32_t v = 0;
    ASSERT_EQ(apci_read_int(board_, &status, &v), APCI_OK);
    const uint32_t handle = status.handle;
    EXPECT_NE(handle, 0u);
    ASSERT_EQ(apci_read_int(board_, &status, &v), APCI_OK);
    EXPECT_EQ(status.handle, handle);
    auto same_object = tc_group(1, APCI_TC_STATUS);
    ASSERT_EQ(apci_read_int(board_, &same_object, &v), APCI_OK);
    EXPECT_EQ(same_object.handle, handle);
}

TEST_F(Board, HandleIsStaleAfterCleanUntilZeroed) {
    auto radius = tc_group(1, APCI_TC_RADIUS);
    ASSERT_EQ(apci_write_double(board_, &radius, 3.0), APCI_OK);
    apci_object_descriptor clean{APCI_TC_BUS, APCI_TC_DEVICE_INIT, APCI_TC_CLEAN, 0, 0};
    ASSERT_EQ(apci_write_int(board_, &clean, 1), APCI_OK) << last_error();
    const uint32_t old = radius.handle;
    double d = 0;
    EXPECT_EQ(apci_read_double(board_, &radius, &d), APCI_STALE_HANDLE);
    EXPECT_EQ(radius.handle, old);  // not silently re-resolved
    EXPECT_EQ(last_error(), "read double 1300/1/1/7: StaleHandle (object handle was discarded "
                            "(TC Clean) or never issued; zero it)");
    EXPECT_EQ(apci_write_double(board_, &radius, 4.0), APCI_STALE_HANDLE);
    radius.handle = 0;
    ASSERT_EQ(apci_read_double(board_, &radius, &d), APCI_OK) << last_error();
    EXPECT_NE(radius.handle, 0u);
    EXPECT_NE(radius.handle, old);
}

TEST_F(Board, HandleOfAnotherObjectIsHandleMismatch) {
    auto status = tc_group(1, APCI_TC_STATUS);
    int32_t v = 0;
    ASSERT_EQ(apci_read_int(board_, &status, &v), APCI_OK);
    auto error = tc_group(1, APCI_TC_ERROR);
    ASSERT_EQ(apci_read_int(board_, &error, &v), APCI_OK);
    error.handle = status.handle;
    EXPECT_EQ(apci_read_int(board_, &error, &v), APCI_HANDLE_MISMATCH);
}

// ---- threading: distinct boards are independent

TEST(Threads, DistinctBoardsMayBeUsedConcurrently) {
    constexpr int kThreads = 4;
    int failures[kThreads] = {};
    std::thread threads[kThreads];
    for (int t = 0; t < kThreads; ++t) {
        threads[t] = std::thread([t, &failures] {
            apci_board* board = nullptr;
            if (apci_open("emu:", &board) != APCI_OK) {
                failures[t] = -1;
                return;
            }
            auto radius = tc_group(1, APCI_TC_RADIUS);
            for (int i = 0; i < 2000; ++i) {
                const double want = t * 1000.0 + i;
                double got = 0;
                if (apci_write_double(board, &radius, want) != APCI_OK ||
                    apci_read_double(board, &radius, &got) != APCI_OK || got != want)
                    ++failures[t];
            }
            apci_close(board);
        });
    }
    for (auto& th : threads) th.join();
    for (int t = 0; t < kThreads; ++t) EXPECT_EQ(failures[t], 0) << "thread " << t;
}

}  // namespace
