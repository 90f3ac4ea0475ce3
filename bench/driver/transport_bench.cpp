// SPDX-License-Identifier: MIT
// One object read round trip (apci_read_int of AxisCount) on each transport,
// through the public C API: inproc (the embedded emulator), unix (the daemon's
// socket), shm (the daemon's dual-port RAM file, served by another process),
// pci (that file seen as a memory BAR and as an I/O BAR through a fake sysfs
// tree), and usb (libusb against the emulated USB board of umockdev, only
// when run under umockdev-wrapper). The daemon is started from build/bin and
// stopped by this program.
// Targets on the 2-core reference machine (docs/performance.md): inproc
// under 100 ns, shm under 2 us, unix under 20 us (medians).
// Beside them, the floors of this machine, with no driver or emulator code:
// one cache line bounced between two processes (what any shared-memory round
// trip costs at least) and 40 bytes bounced over a Unix socket pair by two
// processes that poll (what any socket round trip costs at least), and the
// same with both blocking in recv (what a round trip costs once both sleep).
#include <benchmark/benchmark.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "apci/apci.h"
#if defined(APCI_BENCH_USB)
#include "usb_emulator.h"
#endif

namespace {

// The emulator daemon in a temporary directory, for the whole program.
class DaemonProcess {
  public:
    DaemonProcess() {
        char pattern[] = "/tmp/apci-bench-XXXXXX";
        if (::mkdtemp(pattern) == nullptr) return;
        dir_ = pattern;
        std::string binary = RWMOS_EMU_BINARY;
        std::string socket = "--socket=" + socket_path(), shm = "--shm=" + shm_path(),
                    level = "--log-level=warn";
        std::vector<char*> argv{binary.data(), socket.data(), shm.data(), level.data(), nullptr};
        std::string runtime = "APCI_RUNTIME_DIR=" + dir_;
        std::vector<char*> env;
        for (char** e = environ; *e != nullptr; ++e) env.push_back(*e);
        env.push_back(runtime.data());
        env.push_back(nullptr);
        if (posix_spawn(&pid_, argv[0], nullptr, nullptr, argv.data(), env.data()) != 0) pid_ = -1;
        // Serving once both URIs open.
        for (int i = 0; i < 500 && pid_ > 0; ++i) {
            apci_board* a = nullptr;
            apci_board* b = nullptr;
            const bool up = apci_open(unix_uri().c_str(), &a) == APCI_OK &&
                            apci_open(shm_uri().c_str(), &b) == APCI_OK;
            apci_close(a);
            apci_close(b);
            if (up) return;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        std::fprintf(stderr, "transport_bench: rwmos-emu did not start\n");
    }
    ~DaemonProcess() {
        if (pid_ > 0) {
            ::kill(pid_, SIGTERM);
            int status = 0;
            ::waitpid(pid_, &status, 0);
        }
        if (!dir_.empty()) {
            std::string rm = "rm -rf '" + dir_ + "'";
            if (std::system(rm.c_str()) != 0)
                std::fprintf(stderr, "could not remove %s\n", dir_.c_str());
        }
    }
    std::string socket_path() const { return dir_ + "/rwmos-emu.sock"; }
    std::string shm_path() const { return dir_ + "/dpram"; }
    std::string unix_uri() const { return "unix:" + socket_path(); }
    std::string shm_uri() const { return "shm:" + shm_path(); }
    const std::string& dir() const { return dir_; }

  private:
    std::string dir_;
    pid_t pid_ = -1;
};

DaemonProcess& daemon_process() {
    static DaemonProcess d;
    return d;
}

void read_round_trip(benchmark::State& state, const std::string& uri) {
    apci_board* board = nullptr;
    if (apci_open(uri.c_str(), &board) != APCI_OK) {
        state.SkipWithError(apci_last_error(nullptr));
        return;
    }
    apci_object_descriptor axis_count{1000, 0, 3, 0, 0};
    std::int32_t value = 0;
    for ([[maybe_unused]] auto _ : state) {
        if (apci_read_int(board, &axis_count, &value) != APCI_OK) {
            state.SkipWithError(apci_last_error(board));
            break;
        }
        benchmark::DoNotOptimize(value);
    }
    apci_close(board);
}

// The daemon's dual-port RAM file as BAR 0 of a PCI function in a fake sysfs
// tree ($APCI_SYSFS_ROOT); `io` flags it an I/O BAR (pread/pwrite per word).
std::string fake_pci_board(bool io) {
    const std::string root = daemon_process().dir() + (io ? "/sys-io" : "/sys-mem");
    const std::string dev = root + "/bus/pci/devices/0000:01:00.0";
    std::filesystem::create_directories(dev);
    std::ofstream(dev + "/vendor") << "0x15b8\n";
    std::ofstream(dev + "/device") << "0x8001\n";
    std::ofstream(dev + "/resource") << "0x00000000fe000000 0x00000000fe03ffff "
                                     << (io ? "0x0000000000040101" : "0x0000000000040200") << "\n";
    std::error_code ec;
    std::filesystem::create_symlink(daemon_process().shm_path(), dev + "/resource0", ec);
    ::setenv("APCI_SYSFS_ROOT", root.c_str(), 1);
    return "pci:0000:01:00.0";
}

void BM_ReadRoundTrip_Inproc(benchmark::State& state) {
    read_round_trip(state, "emu:");
}
void BM_ReadRoundTrip_PciMemoryBar(benchmark::State& state) {
    read_round_trip(state, fake_pci_board(false));
}
void BM_ReadRoundTrip_PciIoBar(benchmark::State& state) {
    read_round_trip(state, fake_pci_board(true));
}
#if defined(APCI_BENCH_USB)
void BM_ReadRoundTrip_UsbUmockdev(benchmark::State& state) {
    if (!apci_test::UsbBoard::available()) {
        state.SkipWithError("run under umockdev-wrapper to measure usb:");
        return;
    }
    apci_test::UsbBoard usb;
    read_round_trip(state, usb.uri());
}
BENCHMARK(BM_ReadRoundTrip_UsbUmockdev)->Repetitions(9)->ReportAggregatesOnly(true);
#endif
void BM_ReadRoundTrip_Unix(benchmark::State& state) {
    read_round_trip(state, daemon_process().unix_uri());
}
void BM_ReadRoundTrip_Shm(benchmark::State& state) {
    read_round_trip(state, daemon_process().shm_uri());
}

// ---- Floors

inline void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// Two words on separate cache lines of a shared mapping: the parent writes
// `ping`, a child process answers on `pong`. 0 stops the child.
void BM_Floor_CacheLinePingPong(benchmark::State& state) {
    // cppcheck-suppress invalidFunctionArg ; fd -1 is what MAP_ANONYMOUS takes (mmap(2))
    void* m = ::mmap(nullptr, 4096, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED) {
        state.SkipWithError("mmap failed");
        return;
    }
    auto* ping = static_cast<std::atomic<std::uint32_t>*>(m);
    auto* pong = reinterpret_cast<std::atomic<std::uint32_t>*>(static_cast<char*>(m) + 128);
    ping->store(1);  // 1: idle, 0: stop, anything else: a ping
    pong->store(1);
    const pid_t child = ::fork();
    if (child == 0) {
        std::uint32_t last = 1;
        for (;;) {
            std::uint32_t v;
            while ((v = ping->load(std::memory_order_acquire)) == last) cpu_relax();
            if (v == 0) ::_exit(0);
            pong->store(v, std::memory_order_release);
            last = v;
        }
    }
    std::uint32_t i = 1;
    for ([[maybe_unused]] auto _ : state) {
        if (++i == 0) i = 2;
        ping->store(i, std::memory_order_release);
        while (pong->load(std::memory_order_acquire) != i) cpu_relax();
    }
    ping->store(0, std::memory_order_release);
    ::waitpid(child, nullptr, 0);
    ::munmap(m, 4096);
}

// 40 bytes (the size of an object read frame) to a child process and back
// over a socket pair; both sides poll with MSG_DONTWAIT, never sleeping
// (`polling`), or block in recv.
void socket_pair_ping_pong(benchmark::State& state, bool polling) {
    int sv[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM, 0, sv) != 0) {
        state.SkipWithError("socketpair failed");
        return;
    }
    auto receive = [polling](int fd, char* b) {
        for (;;) {
            const ssize_t n = ::recv(fd, b, 64, polling ? MSG_DONTWAIT : 0);
            if (n >= 0 || (errno != EAGAIN && errno != EINTR)) return n;
        }
    };
    const pid_t child = ::fork();
    if (child == 0) {
        ::close(sv[0]);
        char b[64] = {};
        while (receive(sv[1], b) > 0)
            if (::send(sv[1], b, 40, MSG_NOSIGNAL) != 40) break;
        ::_exit(0);
    }
    ::close(sv[1]);
    char b[64] = {};
    for ([[maybe_unused]] auto _ : state) {
        if (::send(sv[0], b, 40, MSG_NOSIGNAL) != 40 || receive(sv[0], b) <= 0) {
            state.SkipWithError("socket pair failed");
            break;
        }
    }
    ::close(sv[0]);  // the child sees the end and exits
    ::waitpid(child, nullptr, 0);
}
void BM_Floor_UnixSocketPairPolling(benchmark::State& state) {
    socket_pair_ping_pong(state, true);
}
void BM_Floor_UnixSocketPairBlocking(benchmark::State& state) {
    socket_pair_ping_pong(state, false);
}

BENCHMARK(BM_Floor_CacheLinePingPong)->Repetitions(9)->ReportAggregatesOnly(true);
BENCHMARK(BM_Floor_UnixSocketPairPolling)->Repetitions(9)->ReportAggregatesOnly(true);
BENCHMARK(BM_Floor_UnixSocketPairBlocking)->Repetitions(9)->ReportAggregatesOnly(true);
BENCHMARK(BM_ReadRoundTrip_Inproc)->Repetitions(9)->ReportAggregatesOnly(true);
BENCHMARK(BM_ReadRoundTrip_Shm)->Repetitions(9)->ReportAggregatesOnly(true);
BENCHMARK(BM_ReadRoundTrip_Unix)->Repetitions(9)->ReportAggregatesOnly(true);
BENCHMARK(BM_ReadRoundTrip_PciMemoryBar)->Repetitions(9)->ReportAggregatesOnly(true);
BENCHMARK(BM_ReadRoundTrip_PciIoBar)->Repetitions(9)->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
