// SPDX-License-Identifier: MIT
// Test fixtures that run the emulator daemon (build/bin/rwmos-emu) as a child
// process in a fresh temporary directory, wait until it serves, and stop it
// (SIGTERM, then SIGKILL if it hangs) and remove the directory on
// destruction: no process, socket or file outlives the test.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "scratch_dir.h"

namespace apci_test {

// A directory under $TMPDIR (or /tmp), removed with its contents.
using TempDir = test_support::ScratchDir;

struct DaemonOptions {
    bool socket = true;
    bool shm = false;
    // Paths other than the daemon's own temporary directory (e.g. to start
    // a daemon where another one served); empty: the defaults below.
    std::string socket_path;
    std::string shm_path;
    bool option_tc = true;
    std::vector<std::string> extra_args;
};

class Daemon {
  public:
    // Starts the daemon and waits until it serves (at most 10 s). Test
    // failures (ADD_FAILURE) name what went wrong; the result is then null.
    static std::unique_ptr<Daemon> start(const DaemonOptions& options = {});
    ~Daemon();
    Daemon(const Daemon&) = delete;
    Daemon& operator=(const Daemon&) = delete;

    std::string socket_path() const { return socket_path_; }
    std::string shm_path() const { return shm_path_; }
    std::string unix_uri() const { return "unix:" + socket_path(); }
    std::string shm_uri() const { return "shm:" + shm_path(); }
    const TempDir& dir() const noexcept { return dir_; }
    pid_t pid() const noexcept { return pid_; }

    // Sends `signal` and waits for the exit; returns the exit code (128+N
    // for a death by signal N), -1 if it had to be killed after `grace`.
    int stop(int signal = 15, std::chrono::milliseconds grace = std::chrono::seconds(10));
    bool running() const noexcept { return pid_ > 0; }
    // Whatever the daemon wrote on stderr so far.
    std::string log() const;

  private:
    Daemon() = default;
    TempDir dir_;
    std::string socket_path_;
    std::string shm_path_;
    pid_t pid_ = -1;
};

// Runs build/bin/rwmos-emu with `args` to completion (for --help and usage
// errors); returns the exit code and its stdout+stderr in `output`. A daemon
// still running after kRunDaemonLimit (it serves where it should have
// refused) is killed: kStillRunning, and `output` says so.
inline constexpr std::chrono::seconds kRunDaemonLimit{30};
inline constexpr int kStillRunning = -2;
int run_daemon(const std::vector<std::string>& args, std::string& output,
               const std::string& runtime_dir);

// The path of build/bin/rwmos-emu.
const char* daemon_binary();

// Waits until `done()` or `limit` passes; returns done().
template <class F>
bool eventually(F done, std::chrono::milliseconds limit = std::chrono::seconds(10)) {
    const auto until = std::chrono::steady_clock::now() + limit;
    while (!done()) {
        if (std::chrono::steady_clock::now() >= until) return false;
        struct timespec ts {
            0, 2'000'000
        };
        nanosleep(&ts, nullptr);
    }
    return true;
}

}  // namespace apci_test
