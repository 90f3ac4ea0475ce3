// SPDX-License-Identifier: MIT
// The helper threads of `apcictl run` (the writer thread, pipeline.h; the NC front end's reader,
// read_ahead.h) leave the signals sent to the process (SIGTERM, SIGINT, SIGHUP, ...) to the
// caller's thread, whose DeferSignals (run_files.h) holds them while outputs are published; the
// signals a thread's own write or fault raises in it (SIGPIPE, SIGXFSZ, SIGSEGV, ...) stay
// unblocked and end the process as they would on the caller's thread.
#pragma once

#include <pthread.h>

#include <csignal>
#include <thread>
#include <utility>

namespace apci::run::exec {

// Every signal that ends the process and can be sent to it, less those a thread's own write or
// fault raises in that thread.
inline sigset_t process_signals() noexcept {
    sigset_t set;
    sigfillset(&set);
    for (const int sig : {SIGPIPE, SIGXFSZ, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS})
        sigdelset(&set, sig);
    return set;
}

// A thread running `f` with the process's signals blocked (it inherits the mask in force when
// it is made); the caller's mask is as it was. The thread is named `name` (a literal of at most
// 15 characters: what top -H, gdb and /proc/PID/task/TID/comm show).
template <typename F>
std::thread quiet_thread(const char* name, F&& f) {
    const sigset_t block = process_signals();
    sigset_t saved;
    ::pthread_sigmask(SIG_BLOCK, &block, &saved);
    try {
        std::thread t([name, body = std::forward<F>(f)]() mutable {
            ::pthread_setname_np(::pthread_self(), name);
            body();
        });
        ::pthread_sigmask(SIG_SETMASK, &saved, nullptr);
        return t;
    } catch (...) {
        ::pthread_sigmask(SIG_SETMASK, &saved, nullptr);
        throw;
    }
}

}  // namespace apci::run::exec
