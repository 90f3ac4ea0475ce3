// SPDX-License-Identifier: MIT
// A mailbox window on a file mapped MAP_SHARED (a shared-memory file, a PCI
// BAR's sysfs resourceN file, a UIO map), unmapped and closed when destroyed.
#pragma once

#include <memory>
#include <string>

#include "objif/mailbox.h"
#include "objif/status.h"

namespace apci {

struct MapRequest {
    std::string path;
    std::size_t offset = 0;  // bytes from the start of the file (page-aligned)
    std::size_t size = objif::mailbox::kWindowSize;
    bool can_sleep = false;  // futex sleeps: only on ordinary memory
    bool check_size = true;  // refuse a regular file shorter than offset + size
};

// Maps the file. Returns 0 with `out` set, or the errno of the failing call
// with `what` naming it ("open /dev/shm/x", "mmap ..."); a file too short is
// EINVAL. Callers turn the errno into their status.
int map_file(const MapRequest& request, std::unique_ptr<objif::mailbox::Window>& out,
             std::string& what);

// The status of an errno from map_file() or another call on the files of a mapped board (shm:,
// pci:): ENOMEM kNoMemory, ENAMETOOLONG kInvalidArgument, any other (ENODEV, ENXIO, EIO, ...)
// kTransportError. The one place where those backends turn errno into a status.
objif::Status status_of_file_errno(int err) noexcept;

}  // namespace apci
