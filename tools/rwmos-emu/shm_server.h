// SPDX-License-Identifier: MIT
// The daemon's dual-port RAM file (--shm PATH): a file laid out as the
// board's mailbox (objif/mailbox.h, docs/dpram.md), served by one thread
// that takes each request, serves it through BoardHost (serialised with the
// socket clients) and writes the reply. The file is locked (flock) while the
// daemon serves it, so a second daemon on the same path is refused; it is
// removed when the daemon stops, if the path still names it.
//
// The path is never someone else's file: it is created (O_EXCL) or taken
// over only when it is a stale mailbox file of this user (one name, "DRPM"
// header of a known layout); anything else is refused and left untouched.
// The mapping is guarded (objif/mapping_guard.h): a file shrunk under the
// daemon (truncate) ends the serving of the file with an error in the log,
// not the daemon; the socket clients go on being served.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "board_host.h"
#include "objif/mailbox.h"
#include "objif/mapping_guard.h"

namespace rwmos_emu {

class ShmServer {
  public:
    explicit ShmServer(BoardHost& host) : host_(host) {}
    ~ShmServer();
    ShmServer(const ShmServer&) = delete;
    ShmServer& operator=(const ShmServer&) = delete;

    // Creates the file (or takes over a stale one of ours), mode 0660, and
    // formats the mailbox. False with `why` (and the path untouched) if the
    // path is another file, a link, or served by another daemon.
    bool open(const std::string& path, std::string& why);
    // Marks the board serving and starts the serving thread.
    void start();
    // Stops the thread, marks the board stopped (hosts waiting notice at
    // once), removes the file if it is still ours.
    void stop();

    // Whether serving the file ended because it was shrunk or overwritten.
    bool lost() const noexcept { return lost_.load(); }

  private:
    void serve_loop();
    // Why the file can no longer be served ("" while it can).
    std::string damage() const;
    void give_up(const std::string& damage);

    BoardHost& host_;
    std::string path_;
    int fd_ = -1;
    void* map_ = nullptr;
    dev_t dev_ = 0;
    ino_t ino_ = 0;
    std::unique_ptr<objif::MappingGuard> guard_;
    std::unique_ptr<objif::mailbox::MappedWindow> window_;
    std::atomic<bool> stop_{false};
    std::atomic<bool> lost_{false};
    std::thread thread_;
};

}  // namespace rwmos_emu
