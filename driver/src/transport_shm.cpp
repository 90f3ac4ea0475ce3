// SPDX-License-Identifier: MIT
// The shared-memory transport ("shm:PATH"): a file laid out as the board's
// dual-port RAM (docs/dpram.md), served by rwmos-emu --shm PATH in another
// process. The mailbox protocol is MailboxLink's; this file only maps the
// file. Blocking and threading: as MailboxLink. errno becomes a status in
// status_of_file_errno() (mapped_file.h) and nowhere else.
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <new>

#include "mailbox_link.h"
#include "mapped_file.h"
#include "objif/registry.h"
#include "guarded.h"

namespace apci {

using objif::Status;

Status open_shm(const DeviceUri& uri, std::unique_ptr<Transport>& out, std::string& why) noexcept {
    return open_with_options(uri, why, [&](const LinkOptions& options) {
        const Status s = check_path_target(
            uri, options, "shm", "the path of the dual-port RAM file, e.g. shm:/dev/shm/rwmos-emu",
            why);
        if (s != Status::kOk) return s;
        const std::string path = uri.target;
        OpenWindow open_window = [path](std::unique_ptr<objif::mailbox::Window>& window,
                                        std::string& text) {
            MapRequest request;
            request.path = path;
            request.can_sleep = true;
            std::string what;
            const int err = map_file(request, window, what);
            if (err == 0) return Status::kOk;
            text = err == EINVAL ? what : fmt::format("{}: {}", what, std::strerror(err));
            return status_of_file_errno(err);
        };
        return open_framed(std::make_unique<MailboxLink>(std::move(open_window), "shm:" + path),
                           "shm:" + path, options.timeout, out, why);
    });
}

Status list_shm(std::vector<FoundDevice>& out, std::string& why) noexcept {
    return guarded([&] {
        std::vector<objif::RegisteredDaemon> daemons;
        if (!objif::registered_daemons(daemons, why)) return Status::kTransportError;
        for (const auto& d : daemons) {
            if (!d.shm.empty())
                out.push_back(
                    {"shm:" + d.shm, fmt::format("rwmos-emu dual-port RAM file, pid {}", d.pid)});
        }
        return Status::kOk;
    });
}

}  // namespace apci
