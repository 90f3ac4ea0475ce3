// SPDX-License-Identifier: MIT
// The usb: transport through unmodified libusb against an emulated board on
// USB (umockdev serves the usbfs URBs from rwmos::FrameServer; see
// tests/support/usb_emulator.h). Run under umockdev-wrapper.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "apci/apci.h"
#include "text.h"
#include "usb_emulator.h"

namespace {

using test_support::contains;
using apci_test::UsbBoard;
using namespace std::chrono_literals;

apci_object_descriptor axis_count() {
    return {1000, 0, 3, 0, 0};
}

class UsbTransport : public ::testing::Test {
  protected:
    void SetUp() override {
        if (!UsbBoard::available()) GTEST_SKIP() << "not running under umockdev-wrapper";
    }
};

TEST_F(UsbTransport, FirstBoardOpensAndAnswers) {
    UsbBoard usb;
    ASSERT_EQ(usb.problem(), "");
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open("usb:", &b), APCI_OK) << apci_last_error(nullptr);
    auto o = axis_count();
    std::int32_t v = 0;
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(v, 8);
    EXPECT_GE(usb.served(), 1u);
    apci_close(b);
}

TEST_F(UsbTransport, BoardOpensByBusAndAddress) {
    UsbBoard usb;
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(usb.uri().c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    apci_object_descriptor angle{1300, 0, 20, 0, 0};
    ASSERT_EQ(apci_write_double(b, &angle, 42.5), APCI_OK) << apci_last_error(b);
    double v = 0;
    ASSERT_EQ(apci_read_double(b, &angle, &v), APCI_OK);
    EXPECT_EQ(v, 42.5);
    apci_close(b);
}

TEST_F(UsbTransport, OtherAddressIsNotFound) {
    UsbBoard usb;
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open("usb:1:99", &b), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(nullptr), "no ADDI-DATA USB board at bus 1 address 99"))
        << apci_last_error(nullptr);
}

TEST_F(UsbTransport, OlderVendorIdIsABoard) {
    UsbBoard::Options o;
    o.vendor = 0x10E8;
    UsbBoard usb(o);
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open("usb:", &b), APCI_OK) << apci_last_error(nullptr);
    apci_close(b);
}

TEST_F(UsbTransport, OtherVendorIsNotABoard) {
    UsbBoard::Options o;
    o.vendor = 0x1234;
    UsbBoard usb(o);
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open("usb:", &b), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(nullptr), "no ADDI-DATA USB board found"))
        << apci_last_error(nullptr);
}

TEST_F(UsbTransport, DeviceWithoutTheFrameInterfaceIsNotABoard) {
    UsbBoard::Options o;
    o.interface_class = 0x08;  // mass storage
    UsbBoard usb(o);
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open("usb:", &b), APCI_TRANSPORT_ERROR);
}

TEST_F(UsbTransport, ProductIdOptionNarrowsTheMatch) {
    UsbBoard usb;  // product 0x8001
    apci_board* b = nullptr;
    EXPECT_EQ(apci_open("usb:?pid=0x8008", &b), APCI_TRANSPORT_ERROR);
    EXPECT_EQ(apci_open("usb:?pid=0x8008&pid=0x8001", &b), APCI_OK) << apci_last_error(nullptr);
    apci_close(b);
    EXPECT_EQ(apci_open("usb:?pid=banana", &b), APCI_INVALID_ARGUMENT);
}

TEST_F(UsbTransport, BoardThatNeverAnswersTimesOut) {
    UsbBoard::Options o;
    o.answers = false;
    UsbBoard usb(o);
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open("usb:?timeout=200", &b), APCI_OK) << apci_last_error(nullptr);
    auto obj = axis_count();
    std::int32_t v = 0;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(apci_read_int(b, &obj, &v), APCI_TIMEOUT) << apci_last_error(b);
    EXPECT_GE(std::chrono::steady_clock::now() - t0, 190ms);
    EXPECT_TRUE(contains(apci_last_error(b), "no bulk IN (reply) within the timeout"))
        << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 1);
    apci_close(b);
}

TEST_F(UsbTransport, UnplugIsAClearErrorAndReconnectFindsTheBoardOnTheSamePort) {
    UsbBoard usb;
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open(usb.uri().c_str(), &b), APCI_OK) << apci_last_error(nullptr);
    auto o = axis_count();
    std::int32_t v = 0;
    ASSERT_EQ(apci_read_int(b, &o, &v), APCI_OK);
    const std::string before = usb.uri();

    usb.unplug();
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_TRANSPORT_ERROR);
    EXPECT_TRUE(contains(apci_last_error(b), "was unplugged")) << apci_last_error(b);
    EXPECT_TRUE(contains(apci_last_error(b), "apci_reconnect()")) << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 0);
    // What ended it, alone: the device and its port, without the C API's hint.
    std::string cause(apci_link_lost(b, nullptr, 0), '\0');
    ASSERT_EQ(apci_link_lost(b, cause.data(), cause.size() + 1), cause.size());
    EXPECT_TRUE(cause.ends_with(" was unplugged (port 1-2)") || contains(cause, "was unplugged (port "))
        << cause;
    EXPECT_TRUE(contains(apci_last_error(b),
                         cause + "; apci_reconnect() reopens the link once it is back"))
        << apci_last_error(b);
    EXPECT_EQ(apci_reconnect(b), APCI_TRANSPORT_ERROR) << "still unplugged";
    EXPECT_TRUE(contains(apci_last_error(b), "still unplugged")) << apci_last_error(b);

    usb.replug();
    ASSERT_NE(usb.uri(), before) << "a re-plugged device has a new address";
    ASSERT_EQ(apci_reconnect(b), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(apci_is_connected(b), 1);
    o.handle = 0;  // a re-plugged board starts afresh
    EXPECT_EQ(apci_read_int(b, &o, &v), APCI_OK) << apci_last_error(b);
    EXPECT_EQ(v, 8);
    apci_close(b);
}

TEST_F(UsbTransport, ReplyLargerThanOnePacketArrivesWhole) {
    UsbBoard usb;
    apci_board* b = nullptr;
    ASSERT_EQ(apci_open("usb:", &b), APCI_OK) << apci_last_error(nullptr);
    ASSERT_EQ(apci_trace_enable(b, 8192), APCI_OK) << apci_last_error(b);
    apci_profile p{};
    p.kind = APCI_PROFILE_LINE;
    p.axes = 0x01;
    p.feed = 600.0;
    p.target[0] = 20.0;  // 2000 cycles of samples
    ASSERT_EQ(apci_spool_profile(b, &p, nullptr), APCI_OK) << apci_last_error(b);
    apci_motion_status st{};
    ASSERT_EQ(apci_run_until_idle(b, 100000, &st), APCI_OK);
    std::vector<apci_trace_sample> samples(8192);
    std::size_t n = 0;
    ASSERT_EQ(apci_read_trace(b, samples.data(), samples.size(), &n), APCI_OK)
        << apci_last_error(b);
    ASSERT_EQ(n, st.ran);
    EXPECT_EQ(samples[n - 1].position[0], 20.0);
    for (std::size_t i = 1; i < n; ++i) ASSERT_EQ(samples[i].cycle, samples[i - 1].cycle + 1);
    apci_close(b);
}

struct Found {
    std::vector<std::pair<std::string, std::string>> boards;
    static void add(const char* uri, const char* description, void* user) {
        static_cast<Found*>(user)->boards.emplace_back(uri, description);
    }
};

TEST_F(UsbTransport, ListNamesTheUsbBoardWithItsUri) {
    UsbBoard usb;
    Found found;
    ASSERT_EQ(apci_list_devices(Found::add, &found), APCI_OK);
    ASSERT_FALSE(found.boards.empty());
    EXPECT_EQ(found.boards.front().first, usb.uri()) << "USB boards come first";
    EXPECT_TRUE(contains(found.boards.front().second, "15b8:8001")) << found.boards.front().second;
}

}  // namespace
