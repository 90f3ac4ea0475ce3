// SPDX-License-Identifier: MIT
#include "board_sources.h"

#include <gtest/gtest.h>

#include "daemon.h"
#include "fake_sysfs.h"
#if defined(APCI_CONFORMANCE_USB)
#include "usb_emulator.h"
#endif

namespace conformance {
namespace {

using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::FakePciSysfs;

class InprocSource final : public BoardSource {
  public:
    explicit InprocSource(bool option_tc) : option_tc_(option_tc) {}
    std::string uri() const override { return option_tc_ ? "emu:" : "emu:?no-option-tc"; }

  private:
    bool option_tc_;
};

// The daemon with its socket (unix) or only its dual-port RAM file (shm).
class DaemonSource final : public BoardSource {
  public:
    DaemonSource(std::unique_ptr<Daemon> daemon, bool socket)
        : daemon_(std::move(daemon)), socket_(socket) {}
    std::string uri() const override { return socket_ ? daemon_->unix_uri() : daemon_->shm_uri(); }

  private:
    std::unique_ptr<Daemon> daemon_;
    bool socket_;
};

// The daemon's dual-port RAM file seen as a PCI board's BAR 0.
class PciSource final : public BoardSource {
  public:
    PciSource(std::unique_ptr<Daemon> daemon, FakePciSysfs::BarKind kind)
        : daemon_(std::move(daemon)), sysfs_(daemon_->shm_path(), kind) {}
    std::string uri() const override { return sysfs_.uri(); }

  private:
    std::unique_ptr<Daemon> daemon_;
    FakePciSysfs sysfs_;
};

#if defined(APCI_CONFORMANCE_USB)
// An emulated board on USB (umockdev), reached through unmodified libusb.
class UsbSource final : public BoardSource {
  public:
    explicit UsbSource(bool option_tc) : usb_(options(option_tc)) {}
    std::string uri() const override { return usb_.uri(); }
    std::string problem() const { return usb_.problem(); }

  private:
    static apci_test::UsbBoard::Options options(bool option_tc) {
        apci_test::UsbBoard::Options o;
        o.option_tc = option_tc;
        return o;
    }
    apci_test::UsbBoard usb_;
};

std::unique_ptr<BoardSource> make_usb(bool option_tc) {
    auto source = std::make_unique<UsbSource>(option_tc);
    if (!source->problem().empty()) {
        ADD_FAILURE() << source->problem();
        return nullptr;
    }
    return source;
}
#endif

std::unique_ptr<BoardSource> make_inproc(bool option_tc) {
    return std::make_unique<InprocSource>(option_tc);
}

std::unique_ptr<Daemon> start_daemon(bool socket, bool option_tc) {
    DaemonOptions o;
    o.socket = socket;
    o.shm = !socket;
    o.option_tc = option_tc;
    return Daemon::start(o);
}

std::unique_ptr<BoardSource> make_unix(bool option_tc) {
    auto d = start_daemon(true, option_tc);
    return d ? std::make_unique<DaemonSource>(std::move(d), true) : nullptr;
}

std::unique_ptr<BoardSource> make_shm(bool option_tc) {
    auto d = start_daemon(false, option_tc);
    return d ? std::make_unique<DaemonSource>(std::move(d), false) : nullptr;
}

std::unique_ptr<BoardSource> make_pci_mem(bool option_tc) {
    auto d = start_daemon(false, option_tc);
    return d ? std::make_unique<PciSource>(std::move(d), FakePciSysfs::BarKind::kMemory) : nullptr;
}

std::unique_ptr<BoardSource> make_pci_io(bool option_tc) {
    auto d = start_daemon(false, option_tc);
    return d ? std::make_unique<PciSource>(std::move(d), FakePciSysfs::BarKind::kIo) : nullptr;
}

}  // namespace

std::vector<Transport> transports() {
    std::vector<Transport> all{
        {"inproc", make_inproc},   {"unix", make_unix},     {"shm", make_shm},
        {"pci_mem", make_pci_mem}, {"pci_io", make_pci_io},
    };
#if defined(APCI_CONFORMANCE_USB)
    if (apci_test::UsbBoard::available()) all.push_back({"usb", make_usb});
#endif
    return all;
}

}  // namespace conformance
