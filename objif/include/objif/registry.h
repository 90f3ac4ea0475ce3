// SPDX-License-Identifier: MIT
// Where running emulator daemons say what they serve, so `apcictl list` can
// name them (docs/design.md section 7, design). One file per daemon in the
// registry directory, "rwmos-emu.PID", with lines "socket PATH" and
// "shm PATH" (absolute paths; a backslash, a line end or another control
// character written as an escape: \\, \n, \xHH); the daemon writes it after
// it serves and removes it when it stops. Entries of daemons that are gone
// (no such pid), of no pid (0, negative, not in its plain decimal form) and
// entries that do not parse are skipped.
//
// Registry directory: $APCI_RUNTIME_DIR, else $XDG_RUNTIME_DIR/apci, else
// /tmp/apci-UID. docs/rwmos-emu.md describes it. It follows the rules of a
// user's runtime directory (the XDG Base Directory specification, as systemd
// and glib keep them): a directory of this user's own that nobody else may
// enter, mode 0700 when we create it, checked on the opened descriptor
// (fstat), never through a symbolic link; every file in it is opened relative
// to that descriptor with O_NOFOLLOW, and an entry is created with O_EXCL. A
// directory that is not ours (another user made /tmp/apci-UID first) is
// refused, never used: nothing is written there and nothing read from it.
//
// Both sides use it: the daemon writes its entry, the host (libapci's unix:
// and shm: transports) reads them. So it lives in objif, which a host tool
// builds without the emulator (docs/design.md section 2, "Shared declarations").
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace objif {

struct RegisteredDaemon {
    pid_t pid = 0;
    std::string socket;  // "" when the daemon serves no socket; else an absolute path
    std::string shm;     // "" when the daemon serves no shared-memory file; else an absolute path
};

// The largest entry file read (a larger one is skipped): two paths of PATH_MAX
// bytes, each escaped at most four times its length, and their keys.
inline constexpr std::size_t kMaxRegistryEntryBytes = std::size_t{64} * 1024;

std::string registry_dir();

// The registry directory, opened (O_DIRECTORY | O_NOFOLLOW) and checked on
// the descriptor: a directory owned by this process's effective user with no
// permission for group or others. With `create` a missing directory is made
// (mode 0700; its parent must exist). Returns the descriptor (the caller
// closes it), or -1 with `why` naming the directory and what is wrong;
// -1 with `why` empty when the directory is missing and !create.
int open_registry_dir(bool create, std::string& why);

// Writes this process's entry (creating the directory). False with `why` on
// failure; paths that are not absolute are refused.
bool register_daemon(const RegisteredDaemon& self, std::string& why);
// Removes this process's entry, if any (only from a directory that is ours).
void unregister_daemon(pid_t pid);
// Entries of live daemons. A missing directory is an empty list, not an
// error; a directory that is not ours is an error naming it.
bool registered_daemons(std::vector<RegisteredDaemon>& out, std::string& why);

// The entry's escaping of one path (exposed for tests): '\\' and every byte
// below 0x20 or 0x7F escaped, so a path is one line whatever it holds.
std::string escape_registry_path(std::string_view path);
// The inverse; false when `text` holds an escape that escape_registry_path
// does not write, or an unescaped control character.
bool unescape_registry_path(std::string_view text, std::string& path);

}  // namespace objif
