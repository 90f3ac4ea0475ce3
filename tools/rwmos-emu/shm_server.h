// SPDX-License-Identifier: MIT
// The daemon's dual-port RAM file (--shm PATH): a file laid out as the
// board's mailbox (objif/mailbox.h, docs/dpram.md), served by one thread
// that takes each request, serves it through BoardHost (serialised with the
// socket clients) and writes the reply. The file is locked (flock) while the
// daemon serves it, so a second daemon on the same path is refused; it is
// removed when the daemon stops.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "board_host.h"
#include "objif/mailbox.h"

namespace rwmos_emu {

class ShmServer {
  public:
    explicit ShmServer(BoardHost& host) : host_(host) {}
    ~ShmServer();
    ShmServer(const ShmServer&) = delete;
    ShmServer& operator=(const ShmServer&) = delete;

    // Creates (or takes over) the file, mode 0660, formats the mailbox.
    bool open(const std::string& path, std::string& why);
    // Marks the board serving and starts the serving thread.
    void start();
    // Stops the thread, marks the board stopped (hosts waiting notice at
    // once), removes the file if it is still ours.
    void stop();

  private:
    void serve_loop();

    BoardHost& host_;
    std::string path_;
    int fd_ = -1;
    void* map_ = nullptr;
    dev_t dev_ = 0;
    ino_t ino_ = 0;
    std::unique_ptr<objif::mailbox::MappedWindow> window_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

}  // namespace rwmos_emu
