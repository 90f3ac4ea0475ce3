// SPDX-License-Identifier: MIT
#include "fake_sysfs.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace apci_test {

FakePciSysfs::FakePciSysfs(const std::string& resource0, BarKind kind, unsigned vendor) {
    const std::string dir = device_dir();
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/vendor") << fmt::format("{:#06x}\n", vendor);
    std::ofstream(dir + "/device") << "0x8001\n";
    // Lines of include/linux/ioport.h flags: 0x40200 memory, 0x40101 I/O.
    const unsigned long long flags = kind == BarKind::kMemory ? 0x40200 : 0x40101;
    std::ofstream(dir + "/resource")
        << fmt::format("0x00000000fe000000 0x00000000fe03ffff {:#018x}\n", flags)
        << "0x0000000000000000 0x0000000000000000 0x0000000000000000\n";
    std::filesystem::create_symlink(resource0, dir + "/resource0");
    ::setenv("APCI_SYSFS_ROOT", root_.path().c_str(), 1);
}

FakePciSysfs::~FakePciSysfs() {
    ::unsetenv("APCI_SYSFS_ROOT");
}

std::string FakePciSysfs::device_dir() const {
    return root_.path() + "/bus/pci/devices/" + kAddress;
}

}  // namespace apci_test
