// SPDX-License-Identifier: MIT
// Runs a program as a child process for tests: argv (no shell quoting
// issues), optional stdin text, optional extra environment, optional working
// directory; captures stdout, stderr and the exit code.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace test_support {

// The glibc tunables every child runs with unless the test sets its own (run_process).
inline constexpr const char* kFreedMemoryTunables =
    "glibc.malloc.tcache_count=0:glibc.malloc.perturb=165";

struct ProcessResult {
    int exit_code = -1;  // -1: killed by a signal
    std::string out;
    std::string err;
};

inline ProcessResult run_process(const std::vector<std::string>& argv,
                                 const std::string& stdin_text = {},
                                 const std::vector<std::pair<std::string, std::string>>& env = {},
                                 const std::string& cwd = {}) {
    std::signal(SIGPIPE, SIG_IGN);  // a child that exits early must not kill the test
    int in_pipe[2], out_pipe[2], err_pipe[2];
    if (pipe(in_pipe) != 0 || pipe(out_pipe) != 0 || pipe(err_pipe) != 0)
        throw std::runtime_error("pipe failed");
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        dup2(in_pipe[0], 0);
        dup2(out_pipe[1], 1);
        dup2(err_pipe[1], 2);
        for (int fd : {in_pipe[0], in_pipe[1], out_pipe[0], out_pipe[1], err_pipe[0], err_pipe[1]})
            close(fd);
        if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(126);
        // glibc's malloc without its per-thread cache and with freed memory overwritten: a
        // use of freed memory in the child (a FILE used after fclose, a dangling buffer)
        // fails at once instead of only when the heap happens to reuse it (a caller's own
        // GLIBC_TUNABLES, in env or inherited, is kept).
        setenv("GLIBC_TUNABLES", kFreedMemoryTunables, 0);
        for (const auto& [name, value] : env) setenv(name.c_str(), value.c_str(), 1);
        std::vector<char*> args;
        args.reserve(argv.size() + 1);
        for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execv(args[0], args.data());
        _exit(127);
    }
    close(in_pipe[0]);
    close(out_pipe[1]);
    close(err_pipe[1]);
    // Feed stdin and drain stdout/stderr together so no pipe fills up.
    ProcessResult result;
    std::size_t written = 0;
    int in_fd = in_pipe[1];
    if (stdin_text.empty()) {
        close(in_fd);
        in_fd = -1;
    } else {
        fcntl(in_fd, F_SETFL, O_NONBLOCK);
    }
    bool out_open = true, err_open = true;
    char buf[4096];
    while (out_open || err_open || in_fd >= 0) {
        pollfd fds[3] = {{out_open ? out_pipe[0] : -1, POLLIN, 0},
                         {err_open ? err_pipe[0] : -1, POLLIN, 0},
                         {in_fd, POLLOUT, 0}};
        if (poll(fds, 3, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (fds[0].revents) {
            const ssize_t n = read(out_pipe[0], buf, sizeof buf);
            if (n > 0) result.out.append(buf, static_cast<std::size_t>(n)); else out_open = false;
        }
        if (fds[1].revents) {
            const ssize_t n = read(err_pipe[0], buf, sizeof buf);
            if (n > 0) result.err.append(buf, static_cast<std::size_t>(n)); else err_open = false;
        }
        if (in_fd >= 0 && fds[2].revents) {
            const ssize_t n = write(in_fd, stdin_text.data() + written, stdin_text.size() - written);
            if (n > 0) written += static_cast<std::size_t>(n);
            if (n < 0 || written == stdin_text.size()) {
                close(in_fd);
                in_fd = -1;
            }
        }
    }
    close(out_pipe[0]);
    close(err_pipe[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

}  // namespace test_support
