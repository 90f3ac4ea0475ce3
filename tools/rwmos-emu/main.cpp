// SPDX-License-Identifier: MIT
// rwmos-emu: the emulator daemon. One emulated APCI-8001 board, served to
// many clients at once on a Unix socket (--socket) and/or a dual-port RAM
// file (--shm), every request serialised on the one board state.
// docs/design.md sections 6 and 7; docs/rwmos-emu.md.
#include <grp.h>
#include <signal.h>
#include <sys/epoll.h>
#include <sys/resource.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "board_host.h"
#include "log.h"
#include "peer.h"
#include "objif/adaptive_spin.h"
#include "objif/registry.h"
#include "shm_server.h"
#include "socket_server.h"

namespace rwmos_emu {
namespace {

// Exit codes (docs/design.md section 7).
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;
// How long the loop polls for a client's next request before it sleeps: a
// sleeping daemon's wake-up costs tens of microseconds on a virtual machine,
// the poll a fraction of one; the budget halves while requests come slower.
constexpr std::chrono::microseconds kShortestSpin{1};
constexpr std::chrono::microseconds kLongestSpin{50};

struct Options {
    std::string socket;
    std::string shm;
    bool realtime = false;
    bool no_option_tc = false;
    std::size_t max_clients = 64;
    // --idle-timeout: seconds a socket client may send and read nothing
    // before the daemon closes it (0: never). docs/rwmos-emu.md says why 300.
    std::int64_t idle_timeout_s = 300;
    // --trace-memory: the most memory the per-cycle trace may take (BoardConfig::trace_memory).
    std::size_t trace_memory_mib = 64;
    std::string log_level = "info";
    std::string group;  // --group: owner group of the socket and the shm file
    gid_t gid = static_cast<gid_t>(-1);  // resolved from `group`; -1 leaves the daemon's own
    int activated_socket = -1;  // a listening socket from systemd (LISTEN_FDS), or -1
};

// The gid of a group name or number; false if there is no such group.
bool resolve_group(const std::string& name, gid_t& gid) {
    std::vector<char> buf(16384);
    group entry{};
    group* found = nullptr;
    if (::getgrnam_r(name.c_str(), &entry, buf.data(), buf.size(), &found) == 0 && found != nullptr) {
        gid = found->gr_gid;
        return true;
    }
    return false;
}

// Hands the socket or shm file the chosen group (lchown: never through a symlink).
bool give_group(const std::string& path, gid_t gid) {
    if (path.empty() || gid == static_cast<gid_t>(-1)) return true;
    if (::lchown(path.c_str(), static_cast<uid_t>(-1), gid) == 0) return true;
    log(Level::kError, "{}: cannot give it group {}: {}", path, gid, std::strerror(errno));
    return false;
}

// The descriptors the daemon needs besides its clients' (standard streams, epoll, signalfd,
// timers, listener, spare, shm file, the libraries'): a margin.
constexpr rlim_t kOwnDescriptors = 16;

// Each client is a descriptor: the soft limit on open files (often 1024) is raised to the hard
// limit, as a program that does not use select() may (the default --max-clients of up to 4096
// met a soft limit of 1024). Where even that is too small for --max-clients, a warning says what
// happens: newcomers beyond it are told the daemon is out of descriptors.
void raise_open_files_limit(std::size_t max_clients) {
    rlimit limit{};
    if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return;
    if (limit.rlim_cur < limit.rlim_max) {
        rlimit raised = limit;
        raised.rlim_cur = limit.rlim_max;
        if (::setrlimit(RLIMIT_NOFILE, &raised) == 0) limit = raised;
    }
    const rlim_t needed = static_cast<rlim_t>(max_clients) + kOwnDescriptors;
    if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur < needed)
        log(Level::kWarn,
            "--max-clients {} needs about {} open files, the limit is {} (ulimit -n): clients "
            "beyond about {} are told the daemon is out of file descriptors",
            max_clients, needed, limit.rlim_cur,
            limit.rlim_cur > kOwnDescriptors ? limit.rlim_cur - kOwnDescriptors : 0);
}

// `path` made absolute against the working directory (lexically, links kept), for the
// registry: a reader in another directory must find the same file. "" stays "".
std::string absolute(const std::string& path) {
    if (path.empty()) return path;
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::absolute(path, ec);
    return ec ? path : p.lexically_normal().string();
}

// Owns the epoll and signal descriptors.
struct Fds {
    int epoll = -1;
    int signal = -1;
    int timer = -1;  // --realtime pacing
    ~Fds() {
        if (timer >= 0) ::close(timer);
        if (signal >= 0) ::close(signal);
        if (epoll >= 0) ::close(epoll);
    }
};

bool add_watch(int epoll, int fd) {
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.fd = fd;
    return ::epoll_ctl(epoll, EPOLL_CTL_ADD, fd, &ev) == 0;
}

// Every signal whose default action ends the process and that a process
// may catch, except the ones the kernel raises for a fault of the process
// itself (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS, SIGABRT: blocking
// those does not stop them, and they need no cleanup, they are a crash).
// SIGPIPE is ignored instead (a client that vanished is an EPIPE).
constexpr int kShutdownSignals[] = {SIGHUP,  SIGINT,  SIGQUIT,   SIGTERM,  SIGUSR1,
                                    SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF,  SIGXCPU,
                                    SIGXFSZ, SIGPOLL, SIGPWR,    SIGSTKFLT};

// Each of them arrives through a signalfd in the event loop, so a shutdown
// happens between requests, never inside one, and always cleans up the same
// way. Blocked before any thread starts, so every thread inherits the mask.
// The real-time signals (SIGRTMIN..SIGRTMAX) end a process too: included.
int block_shutdown_signals() {
    sigset_t set;
    sigemptyset(&set);
    for (const int sig : kShutdownSignals) sigaddset(&set, sig);
    for (int sig = SIGRTMIN; sig <= SIGRTMAX; ++sig) sigaddset(&set, sig);
    if (::pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return -1;
    ::signal(SIGPIPE, SIG_IGN);
    return ::signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
}

// "SIGHUP", ... for the log; sigabbrev_np knows every signal but the real-time ones.
std::string signal_name(int sig) {
    if (sig >= SIGRTMIN && sig <= SIGRTMAX) return fmt::format("SIGRTMIN+{}", sig - SIGRTMIN);
    const char* abbrev = ::sigabbrev_np(sig);
    return abbrev != nullptr ? fmt::format("SIG{}", abbrev) : fmt::format("signal {}", sig);
}

// SIGTERM and SIGINT are the requested stop: exit 0. Any other shutdown
// signal stops the daemon the same way, then exits 128 + its number (what a
// shell reports for a process that signal ended), so whoever started it can
// tell.
int exit_code_for(int sig) {
    return sig == SIGTERM || sig == SIGINT ? kExitOk : 128 + sig;
}

// The listening socket systemd passed (socket activation, sd_listen_fds(3)): fd 3 when
// LISTEN_PID is this process and LISTEN_FDS is 1; -1 when none was passed. The variables
// are removed, so no child would take them for its own. More than one socket: -2 with `why`.
int systemd_socket(std::string& why) {
    const char* pid = std::getenv("LISTEN_PID");
    const char* count = std::getenv("LISTEN_FDS");
    const bool ours = pid != nullptr && count != nullptr &&
                      std::strtoll(pid, nullptr, 10) == static_cast<long long>(::getpid());
    const long long n = ours ? std::strtoll(count, nullptr, 10) : 0;
    ::unsetenv("LISTEN_PID");
    ::unsetenv("LISTEN_FDS");
    ::unsetenv("LISTEN_FDNAMES");
    if (n <= 0) return -1;
    if (n > 1) {
        why = fmt::format("systemd passed {} sockets; rwmos-emu serves one (one ListenStream= "
                          "in rwmos-emu.socket)", n);
        return -2;
    }
    return 3;  // SD_LISTEN_FDS_START
}

// The board's transports: the Unix socket (the one systemd passed, or one of our own) and the
// dual-port RAM file. False, logged, when one cannot be set up.
bool open_transports(const Options& o, SocketServer& sockets, ShmServer& shm) {
    std::string why;
    if (o.activated_socket >= 0) {
        if (!sockets.adopt(o.activated_socket, o.socket, why)) {
            log(Level::kError, "{}", why);
            return false;
        }
    } else if (!o.socket.empty() && !sockets.open(o.socket, o.gid, why)) {
        log(Level::kError, "{}", why);
        return false;
    }
    if (!o.shm.empty() && !shm.open(o.shm, why)) {
        log(Level::kError, "{}", why);
        return false;
    }
    return give_group(o.shm, o.gid);
}

// --realtime: every millisecond the clock catches up with wall time (docs/design.md section
// 5). False, logged, when the timer cannot be set up.
bool start_pacing(Fds& fds, BoardHost& host) {
    fds.timer = ::timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC | TFD_NONBLOCK);
    const itimerspec every_ms{{0, 1'000'000}, {0, 1'000'000}};
    if (fds.timer < 0 || ::timerfd_settime(fds.timer, 0, &every_ms, nullptr) != 0 ||
        !add_watch(fds.epoll, fds.timer)) {
        log(Level::kError, "--realtime: cannot set up the pacing timer: {}",
            std::strerror(errno));
        return false;
    }
    host.pace(std::chrono::steady_clock::now());
    return true;
}

// How the event loop ended: the daemon's exit code, and what the clients are told.
struct LoopEnd {
    int exit_code = kExitOk;
    std::string stop_reason;
    bool running = true;
};

// The events of one wait: a shutdown signal ends the loop (`end` says how), the pacing timer
// moves the clock on, the sockets are served. True when a client was served.
bool dispatch(const epoll_event* events, int n, const Fds& fds, BoardHost& host,
              SocketServer& sockets, LoopEnd& end) {
    bool served_client = false;
    for (int i = 0; i < n; ++i) {
        const int fd = events[i].data.fd;
        if (fd == fds.signal) {
            signalfd_siginfo info{};
            if (::read(fds.signal, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
                const int sig = static_cast<int>(info.ssi_signo);
                end.stop_reason = fmt::format("shutting down ({})", signal_name(sig));
                log(Level::kInfo, "{}: shutting down", signal_name(sig));
                end.exit_code = exit_code_for(sig);
                end.running = false;
            }
        } else if (fd == fds.timer) {
            std::uint64_t expirations = 0;
            if (::read(fds.timer, &expirations, sizeof expirations) > 0)
                host.pace(std::chrono::steady_clock::now());
        } else if (fd == sockets.listen_fd()) {
            sockets.on_listen_ready();
        } else if (fd == sockets.idle_timer_fd()) {
            sockets.on_idle_timer();
        } else {
            sockets.on_client_ready(fd, events[i].events);
            served_client = true;
        }
    }
    return served_client;
}

// Serves until a shutdown signal. Out of memory, or any other failure in the loop, ends the
// daemon the way a signal does (clients told, socket, file and registry entry removed),
// never with them left behind.
LoopEnd event_loop(const Fds& fds, BoardHost& host, SocketServer& sockets) {
    LoopEnd end;
    // After serving a client the loop polls for the next request for a learned
    // budget before it sleeps in epoll_wait (docs/performance.md, "Transports").
    objif::AdaptiveSpin spin(kShortestSpin, kLongestSpin);
    bool served_client = false;
    try {
        while (end.running) {
            epoll_event events[64];
            int n = 0;
            const auto start = std::chrono::steady_clock::now();
            if (served_client) {
                const auto until = start + spin.budget();
                do {
                    n = ::epoll_wait(fds.epoll, events, 64, 0);
                } while (n == 0 && std::chrono::steady_clock::now() < until);
            }
            if (n == 0) n = ::epoll_wait(fds.epoll, events, 64, sockets.wait_ms());
            if (served_client) spin.learn(std::chrono::steady_clock::now() - start);
            served_client = false;
            if (n < 0) {
                if (errno == EINTR) continue;
                log(Level::kError, "epoll_wait: {}", std::strerror(errno));
                end.exit_code = kExitFailure;
                break;
            }
            served_client = dispatch(events, n, fds, host, sockets, end);
            // Clients whose requests outlasted their turn are served after every other.
            if (end.running) sockets.after_events();
        }
    } catch (const std::exception& e) {
        log(Level::kError, "internal error: {}; shutting down", e.what());
        end.stop_reason = "shutting down (internal error)";
        end.exit_code = kExitFailure;
    }
    return end;
}

int serve(const Options& o) {
    Level level{};
    parse_level(o.log_level, level);
    set_log_level(level);

    Fds fds;
    fds.signal = block_shutdown_signals();
    fds.epoll = ::epoll_create1(EPOLL_CLOEXEC);
    if (fds.signal < 0 || fds.epoll < 0 || !add_watch(fds.epoll, fds.signal)) {
        log(Level::kError, "cannot set up the event loop: {}", std::strerror(errno));
        return kExitFailure;
    }

    raise_open_files_limit(o.max_clients);
    rwmos::BoardConfig config;
    config.option_tc = !o.no_option_tc;
    config.trace_memory = o.trace_memory_mib << 20;
    BoardHost host(config, host_process_alive);
    SocketServer sockets(host, fds.epoll,
                         ClientLimits{o.max_clients, std::chrono::seconds(o.idle_timeout_s)});
    ShmServer shm(host);
    if (!open_transports(o, sockets, shm)) return kExitFailure;
    const std::string& socket_path = sockets.path();
    shm.start();
    if (o.realtime && !start_pacing(fds, host)) return kExitFailure;

    std::string why;
    objif::RegisteredDaemon self{::getpid(), absolute(socket_path), absolute(o.shm)};
    if (!objif::register_daemon(self, why))
        log(Level::kWarn, "apcictl list will not see this daemon: {}", why);
    log(Level::kInfo, "serving one board (optionTC {}, {} time){}{}{}{}",
        o.no_option_tc ? "off" : "on", o.realtime ? "wall" : "virtual",
        socket_path.empty() ? "" : (o.activated_socket >= 0 ? " on socket (from systemd) " : " on socket "),
        socket_path,
        o.shm.empty() ? "" : " and dual-port RAM file ", o.shm);

    const LoopEnd end = event_loop(fds, host, sockets);

    sockets.close_all(end.stop_reason);
    shm.stop();
    objif::unregister_daemon(self.pid);
    const ServedCounts counts = host.counts();
    log(Level::kInfo, "stopped: served {} request frames ({} answered with Error)", counts.frames,
        counts.rejected);
    return end.exit_code;
}

int run(int argc, char** argv) {
    CLI::App app(
        "rwmos-emu - the RWMOS emulator daemon: one emulated APCI-8001 board served to "
        "many clients",
        "rwmos-emu");
    Options o;
    app.add_option("--socket", o.socket,
                   "Serve wire frames on this Unix socket (created mode 0660; a stale socket is "
                   "removed, a live one refused)");
    app.add_option("--shm", o.shm,
                   "Also serve a dual-port RAM mailbox in this file (created mode 0660), e.g. "
                   "/dev/shm/rwmos-emu");
    app.add_flag("--realtime", o.realtime,
                 "Pace the interpolation clock to wall time (one cycle per InterpolationCycle); "
                 "without it the clock runs only when a client steps it (virtual time)");
    app.add_flag("--no-option-tc", o.no_option_tc,
                 "Emulate firmware without optionTC: the TC module (bus 1300) is absent");
    app.add_option("--max-clients", o.max_clients,
                   "Most socket clients connected at once (default 64); clients that hung up "
                   "are not counted. One more is told 'too many clients (N)' and closed")
        ->check(CLI::Range(1, 4096));
    app.add_option("--idle-timeout", o.idle_timeout_s,
                   "Close a socket client that sent and read nothing for SECONDS, telling it "
                   "why (default 300; 0 = never; at most 86400)")
        ->type_name("SECONDS")
        ->check(CLI::Range(0, 86400));
    app.add_option("--trace-memory", o.trace_memory_mib,
                   "Most memory the per-cycle trace may take, in MiB (default 64, 1..1152): a "
                   "client asking for a larger trace ring is refused with NoMemory")
        ->type_name("MIB")
        ->check(CLI::Range(1, 1152));
    app.add_option("--group", o.group,
                   "Group of the socket and the dual-port RAM file, so its members may connect "
                   "(default: the daemon's own group)");
    app.add_option("--log-level", o.log_level, "error, warn, info (default) or debug")
        ->check(CLI::IsMember({"error", "warn", "info", "debug"}));
    app.set_version_flag("--version", fmt::format("rwmos-emu (apci8001) {}", APCI8001_VERSION));
    app.footer(
        "Clients open the board with the device URI unix:PATH or shm:PATH (libapci, "
        "apcictl --device). SIGTERM or SIGINT stops the daemon and removes its socket, its "
        "file and its registry entry; so does every other signal that would end it (SIGHUP, "
        "SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF, SIGXCPU, SIGXFSZ, SIGPOLL, "
        "SIGPWR, SIGSTKFLT, real-time signals); SIGPIPE is ignored. Logs go to stderr (with "
        "their syslog priority when stderr is the journal). A listening socket passed by "
        "systemd (socket activation, LISTEN_FDS) is served in place of --socket's own.\n"
        "Exit codes: 0 ok (stopped by SIGTERM or SIGINT), 1 could not serve (or --help or "
        "--version could not be written), 2 usage, 128+N stopped by signal N.");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        if (code != 0) return kExitUsage;
        // --help or --version: what they printed must have reached standard output (a full
        // disk, a closed descriptor), else say so and fail, as apcictl does.
        if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
            std::fprintf(stderr, "rwmos-emu: cannot write standard output: %s\n",
                         std::strerror(errno));
            return kExitFailure;
        }
        return kExitOk;
    }
    if (!o.group.empty() && !resolve_group(o.group, o.gid)) {
        std::fprintf(stderr, "rwmos-emu: --group %s: no such group\n", o.group.c_str());
        return kExitUsage;
    }
    std::string why;
    o.activated_socket = systemd_socket(why);
    if (o.activated_socket == -2) {
        std::fprintf(stderr, "rwmos-emu: %s\n", why.c_str());
        return kExitUsage;
    }
    if (o.socket.empty() && o.shm.empty() && o.activated_socket < 0) {
        std::fprintf(stderr, "rwmos-emu: give --socket PATH, --shm PATH or both (see --help)\n");
        return kExitUsage;
    }
    return serve(o);
}

}  // namespace
}  // namespace rwmos_emu

int main(int argc, char** argv) {
    try {
        return rwmos_emu::run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rwmos-emu: internal error: %s\n", e.what());
    } catch (...) {
        std::fprintf(stderr, "rwmos-emu: internal error\n");
    }
    return 1;
}
