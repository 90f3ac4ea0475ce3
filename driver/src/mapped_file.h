// SPDX-License-Identifier: MIT
// A mailbox window on a file mapped MAP_SHARED (a shared-memory file, a PCI
// BAR's sysfs resourceN file, a UIO map), unmapped and closed when destroyed.
#pragma once

#include <memory>
#include <string>

#include "objif/mailbox.h"

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

}  // namespace apci
