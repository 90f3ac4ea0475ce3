// SPDX-License-Identifier: MIT
// The shared-memory transport ("shm:PATH"): a file laid out as the board's
// dual-port RAM (docs/dpram.md), served by rwmos-emu --shm PATH in another
// process. The mailbox protocol is MailboxLink's; this file only maps the
// file. Blocking and threading: as MailboxLink. errno becomes a status in
// status_of_errno() and nowhere else.
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <new>

#include "mailbox_link.h"
#include "mapped_file.h"
#include "objif/registry.h"
#include "guarded.h"

namespace apci {
namespace {

using objif::Status;

// The one place where this backend turns errno into a status.
Status status_of_errno(int err) noexcept {
    switch (err) {
        case ENOMEM:
            return Status::kNoMemory;
        case ENAMETOOLONG:
            return Status::kInvalidArgument;
        default:
            return Status::kTransportError;
    }
}

}  // namespace

Status open_shm(const DeviceUri& uri, std::unique_ptr<Transport>& out, std::string& why) noexcept {
    return guarded([&] {
        LinkOptions options;
        Status s = parse_link_options(uri, options, why);
        if (s != Status::kOk) return s;
        if (!options.rest.empty()) {
            why = fmt::format("unknown shm: option '{}' (known: timeout=MS)", options.rest.front());
            return Status::kInvalidArgument;
        }
        if (uri.target.empty()) {
            why = "shm: needs the path of the dual-port RAM file, e.g. shm:/dev/shm/rwmos-emu";
            return Status::kInvalidArgument;
        }
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
            return status_of_errno(err);
        };
        auto link = std::make_unique<MailboxLink>(std::move(open_window), "shm:" + path);
        s = link->open(why);
        if (s != Status::kOk) return s;
        out = std::make_unique<FrameTransport>(std::move(link), "shm:" + path, options.timeout);
        return Status::kOk;
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
