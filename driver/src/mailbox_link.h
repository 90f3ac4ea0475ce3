// SPDX-License-Identifier: MIT
// A FrameLink over the dual-port RAM mailbox (objif/mailbox.h), shared by
// the backends that reach a board through a window of memory: shm: (a file
// the emulator serves), pci: (a board's BAR through sysfs or UIO). The
// backend supplies how to open the window; the mailbox protocol is here once.
// Blocking: exchange() spins briefly, then sleeps (futex) or polls until the
// reply, at most the timeout. Threading: one caller at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "frame_transport.h"
#include "objif/mailbox.h"

namespace apci {

// Opens (or re-opens) the window; kOk with `out` set, or a status and `why`.
using OpenWindow =
    std::function<objif::Status(std::unique_ptr<objif::mailbox::Window>& out, std::string& why)>;

class MailboxLink final : public FrameLink {
  public:
    // `name` ("shm:/path") is used in failure texts.
    MailboxLink(OpenWindow open, std::string name)
        : open_(std::move(open)), name_(std::move(name)) {}

    // Opens the window and checks its layout and that a board serves it.
    objif::Status open(std::string& why) noexcept;

    objif::Status exchange(std::span<const std::uint8_t> request, std::uint32_t sequence,
                           std::vector<std::uint8_t>& reply, Millis timeout,
                           std::string& why) noexcept override;
    objif::Status reconnect(std::string& why) noexcept override { return open(why); }
    bool connected() const noexcept override { return window_ != nullptr; }
    std::string lost_reason() const override { return window_ ? std::string() : lost_; }

    // The file a window maps, as /proc/PID/maps names it: to tell whether the process whose
    // pid holds the host lock is a host of this mailbox or another that got the pid later.
    struct MappedFileId {
        std::string device;  // "MAJOR:MINOR", hex
        std::uint64_t inode = 0;
    };

  private:
    OpenWindow open_;
    MappedFileId mapped_;  // inode 0: unknown (not a mapping)
    std::string name_;
    std::unique_ptr<objif::mailbox::Window> window_;
    std::uint32_t generation_ = 0;  // the board's generation when opened
    // How long to spin for a reply before sleeping: learnt from the replies.
    // Up to 50 us, as the daemon socket's client: that covers a board woken
    // from its futex sleep (tens of us on a virtual machine), so neither side
    // settles into sleeping on every exchange (docs/performance.md).
    objif::mailbox::AdaptiveSpin spin_{std::chrono::microseconds(1), std::chrono::microseconds(50)};
    std::string lost_;
};

}  // namespace apci
