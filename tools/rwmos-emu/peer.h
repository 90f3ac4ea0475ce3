// SPDX-License-Identifier: MIT
// Who the daemon's hosts are, for the motion claim (rwmos/motion_claim.h,
// docs/motion-claim.md): a socket client by its connection and the kernel's word for its
// process (SO_PEERCRED), a dual-port RAM host by the token of the mailbox's host lock, which is
// its process id (docs/dpram.md). The names come from /proc/PID/comm.
#pragma once

#include <cstdint>

#include "rwmos/motion_claim.h"

namespace rwmos_emu {

// The socket client `id` on the connected socket `fd`.
rwmos::Host socket_host(int fd, std::uint64_t id);

// The mailbox host whose host lock token is `token`. Its key keeps it apart from every
// socket client's.
rwmos::Host mailbox_host(std::uint32_t token);

// Whether the process of a mailbox host still runs: the same pid with the same start time
// (a pid the kernel handed to another process since is not the holder).
bool host_process_alive(const rwmos::Host& host);

}  // namespace rwmos_emu
