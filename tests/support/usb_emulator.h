// SPDX-License-Identifier: MIT
// An emulated APCI board on USB for tests, through umockdev: a testbed with
// one USB device (ADDI-DATA vendor ID, the frame interface of
// objif/usb_layout.h) whose usbfs ioctls are served by a handler, the way
// libusb's own tests (libusb/tests/umockdev.c) drive libusb against a fake
// device. Bulk OUT URBs feed an emulated board (rwmos::FrameStream over a
// FrameServer); bulk IN URBs are completed with its reply frames. libusb and
// libapci run unmodified against it.
//
// The process must run under umockdev's preload library
// (umockdev-wrapper, or LD_PRELOAD=libumockdev-preload.so.0); check
// available() first.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace apci_test {

class UsbBoard {
  public:
    struct Options {
        std::uint16_t vendor = 0x15B8;
        std::uint16_t product = 0x8001;
        bool option_tc = true;
        // The frame interface's class; anything but 0xFF is not a board.
        std::uint8_t interface_class = 0xFF;
        // When false the board takes requests but never answers (a hung firmware).
        bool answers = true;
    };

    // True when the process runs under umockdev's preload library.
    static bool available();

    explicit UsbBoard(const Options& options);
    UsbBoard() : UsbBoard(Options{}) {}
    ~UsbBoard();
    UsbBoard(const UsbBoard&) = delete;
    UsbBoard& operator=(const UsbBoard&) = delete;

    // "usb:1:N" for this device.
    std::string uri() const;
    int bus() const;
    int address() const;

    // Pulls the cable: every ioctl on the device answers ENODEV, and the
    // device leaves sysfs. The board's state is lost, as on a real board.
    void unplug();
    // Plugs it back in on the same port (a fresh board).
    void replug();

    // Request frames the board served so far.
    std::uint64_t served() const;
    // Why the device could not be set up in the testbed ("" if it was).
    std::string problem() const;

    struct Impl;

  private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace apci_test
