// SPDX-License-Identifier: MIT
// Where the conformance suite gets a fresh board for one test: one source per
// transport that can run here. Each gives a device URI for apci_open() and
// owns whatever serves it (a daemon process, a fake sysfs tree, a umockdev
// testbed), torn down when the source is destroyed.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace conformance {

class BoardSource {
  public:
    virtual ~BoardSource() = default;
    // The URI of a fresh board, with (true) or without (false) optionTC.
    virtual std::string uri() const = 0;
};

// Makes a source for a fresh board; null (with a test failure recorded) if
// it could not be started.
using MakeSource = std::unique_ptr<BoardSource> (*)(bool option_tc);

struct Transport {
    std::string name;  // gtest parameter name: inproc, unix, shm, ...
    MakeSource make;
    // gtest prints the parameter by its name.
    friend void PrintTo(const Transport& t, std::ostream* os) { *os << t.name; }
};

// Every transport this binary can run: inproc, unix, shm, pci (the daemon's
// dual-port RAM file as a memory BAR and as an I/O BAR), and usb (an
// emulated board behind umockdev) when run under umockdev-wrapper.
std::vector<Transport> transports();

}  // namespace conformance
