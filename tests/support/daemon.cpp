// SPDX-License-Identifier: MIT
#include "daemon.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "objif/mailbox.h"
#include "process.h"
#include "text.h"

namespace apci_test {
namespace {

// The test's environment with the daemon's runtime directory, and glibc's malloc made strict
// as for every child of a test (process.h) unless the test runs with its own tunables.
std::vector<std::string> environment_with(const std::string& runtime_dir) {
    std::vector<std::string> env;
    bool tunables = false;
    for (char** e = environ; *e != nullptr; ++e) {
        if (std::strncmp(*e, "APCI_RUNTIME_DIR=", 17) != 0) env.emplace_back(*e);
        if (std::strncmp(*e, "GLIBC_TUNABLES=", 15) == 0) tunables = true;
    }
    env.push_back("APCI_RUNTIME_DIR=" + runtime_dir);
    if (!tunables) env.push_back(std::string("GLIBC_TUNABLES=") + test_support::kFreedMemoryTunables);
    return env;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
    std::vector<char*> p;
    p.reserve(strings.size() + 1);
    for (auto& s : strings) p.push_back(s.data());
    p.push_back(nullptr);
    return p;
}

pid_t spawn(const std::vector<std::string>& args, const std::string& output_file,
            const std::string& runtime_dir) {
    std::vector<std::string> argv{daemon_binary()};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<std::string> env = environment_with(runtime_dir);
    auto argv_p = pointers(argv);
    auto env_p = pointers(env);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output_file.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0600);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, argv_p[0], &actions, nullptr, argv_p.data(), env_p.data());
    posix_spawn_file_actions_destroy(&actions);
    return rc == 0 ? pid : -1;
}

bool socket_accepts(const std::string& path) {
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    ::close(fd);
    return ok;
}

bool mailbox_serving(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::uint32_t header[16] = {};
    if (!f.read(reinterpret_cast<char*>(header), sizeof header)) return false;
    return header[objif::mailbox::kOffSignature / 4] == objif::mailbox::kSignature &&
           header[objif::mailbox::kOffBoardState / 4] ==
               static_cast<std::uint32_t>(objif::mailbox::BoardState::kServing);
}

int exit_code_of(int status) {
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return -1;
}

}  // namespace

const char* daemon_binary() {
    return RWMOS_EMU_BINARY;
}

std::unique_ptr<Daemon> Daemon::start(const DaemonOptions& options) {
    std::unique_ptr<Daemon> d(new Daemon);
    if (d->dir_.path().empty()) {
        ADD_FAILURE() << "could not make the daemon's temporary directory: " << std::strerror(errno);
        return nullptr;
    }
    d->socket_path_ =
        options.socket_path.empty() ? d->dir_.file("rwmos-emu.sock") : options.socket_path;
    d->shm_path_ = options.shm_path.empty() ? d->dir_.file("dpram") : options.shm_path;
    std::vector<std::string> args;
    if (options.socket) args.insert(args.end(), {"--socket", d->socket_path()});
    if (options.shm) args.insert(args.end(), {"--shm", d->shm_path()});
    if (!options.option_tc) args.emplace_back("--no-option-tc");
    args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
    d->pid_ = spawn(args, d->dir_.file("daemon.log"), d->dir_.path());
    if (d->pid_ < 0) {
        ADD_FAILURE() << "cannot start " << daemon_binary();
        return nullptr;
    }
    bool exited = false;
    const bool ready = eventually([&] {
        int status = 0;
        if (::waitpid(d->pid_, &status, WNOHANG) == d->pid_) {
            exited = true;
            d->pid_ = -1;
            return true;
        }
        return (!options.socket || socket_accepts(d->socket_path())) &&
               (!options.shm || mailbox_serving(d->shm_path()));
    });
    if (!ready || exited) {
        ADD_FAILURE() << "rwmos-emu did not start serving: " << d->log();
        return nullptr;
    }
    return d;
}

Daemon::~Daemon() {
    if (pid_ > 0) stop(SIGKILL);
}

int Daemon::stop(int signal, std::chrono::milliseconds grace) {
    if (pid_ <= 0) return -1;
    ::kill(pid_, signal);
    int status = 0;
    const bool done = eventually([&] { return ::waitpid(pid_, &status, WNOHANG) == pid_; }, grace);
    if (!done) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        pid_ = -1;
        return -1;
    }
    pid_ = -1;
    return exit_code_of(status);
}

std::string Daemon::log() const {
    return test_support::read_text(dir_.file("daemon.log"));
}

int run_daemon(const std::vector<std::string>& args, std::string& output,
               const std::string& runtime_dir) {
    const std::string file = runtime_dir + "/run.out";
    ::unlink(file.c_str());
    const pid_t pid = spawn(args, file, runtime_dir);
    if (pid < 0) return -1;
    // A daemon expected to stop at once that serves instead (a check that let it through) is
    // stopped after kRunDaemonLimit, so its test fails then, naming why, instead of waiting
    // for the test program's own time limit.
    int status = 0;
    const auto until = std::chrono::steady_clock::now() + kRunDaemonLimit;
    pid_t done = 0;
    while ((done = ::waitpid(pid, &status, WNOHANG)) == 0 &&
           std::chrono::steady_clock::now() < until)
        ::usleep(10'000);
    if (done == 0) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        output = test_support::read_text(file) + "\n[still running after " +
                 std::to_string(kRunDaemonLimit.count()) + " s: stopped by the test]\n";
        return kStillRunning;
    }
    output = test_support::read_text(file);
    return exit_code_of(status);
}

}  // namespace apci_test
