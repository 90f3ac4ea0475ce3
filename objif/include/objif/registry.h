// SPDX-License-Identifier: MIT
// Where running emulator daemons say what they serve, so `apcictl list` can
// name them (docs/design.md section 7, design). One file per daemon in the
// registry directory, "rwmos-emu.PID", with lines "socket PATH" and
// "shm PATH"; the daemon writes it after it serves and removes it when it
// stops. Entries of daemons that are gone (no such pid) are skipped.
//
// Registry directory: $APCI_RUNTIME_DIR, else $XDG_RUNTIME_DIR/apci, else
// /tmp/apci-UID. docs/rwmos-emu.md describes it.
//
// Both sides use it: the daemon writes its entry, the host (libapci's unix:
// and shm: transports) reads them. So it lives in objif, which a host tool
// builds without the emulator (docs/design.md section 2, "Shared declarations").
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace objif {

struct RegisteredDaemon {
    pid_t pid = 0;
    std::string socket;  // "" when the daemon serves no socket
    std::string shm;     // "" when the daemon serves no shared-memory file
};

std::string registry_dir();

// Writes this process's entry (creating the directory, mode 0700). False with
// `why` on failure.
bool register_daemon(const RegisteredDaemon& self, std::string& why);
// Removes this process's entry, if any.
void unregister_daemon(pid_t pid);
// Entries of live daemons. A missing directory is an empty list, not an error.
bool registered_daemons(std::vector<RegisteredDaemon>& out, std::string& why);

}  // namespace objif
