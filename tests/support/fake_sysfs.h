// SPDX-License-Identifier: MIT
// A fake sysfs PCI tree for the pci: transport: one ADDI-DATA function whose
// BAR 0 "resource0" is the emulator daemon's dual-port RAM file, flagged as
// a memory BAR (mapped) or an I/O BAR (pread/pwrite). Points the driver at
// it with $APCI_SYSFS_ROOT while it lives.
#pragma once

#include <string>

#include "daemon.h"

namespace apci_test {

class FakePciSysfs {
  public:
    enum class BarKind { kMemory, kIo };
    static constexpr const char* kAddress = "0000:01:00.0";

    // `resource0` is the file the BAR shows (the daemon's shm file).
    FakePciSysfs(const std::string& resource0, BarKind kind, unsigned vendor = 0x15b8);
    ~FakePciSysfs();
    FakePciSysfs(const FakePciSysfs&) = delete;
    FakePciSysfs& operator=(const FakePciSysfs&) = delete;

    std::string uri() const { return std::string("pci:") + kAddress; }
    std::string device_dir() const;

  private:
    TempDir root_;
};

}  // namespace apci_test
