// SPDX-License-Identifier: MIT
// rwmos-emu's security rules (docs/hardening.md, "Daemon security"): it
// listens on a Unix socket only, never on a network port; it does not follow
// a symlink for its socket or its shm file; socket and shm file are 0660 and
// their group is configurable (--group).
#include <grp.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "daemon.h"

namespace {

using apci_test::Daemon;
using apci_test::DaemonOptions;
using apci_test::TempDir;

std::string first_line(const std::string& path) {
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);
    return line;
}

// The inodes of the sockets listed in a /proc/net table (column "inode").
std::set<std::string> socket_inodes(const std::string& table) {
    std::set<std::string> inodes;
    std::ifstream f(table);
    std::string line;
    std::getline(f, line);  // header
    while (std::getline(f, line)) {
        std::istringstream in(line);
        std::string field;
        std::vector<std::string> fields;
        while (in >> field) fields.push_back(field);
        // tcp/udp: inode is field 10; unix: field 7.
        const std::size_t at = table.ends_with("unix") ? 6 : 9;
        if (fields.size() > at) inodes.insert(fields[at]);
    }
    return inodes;
}

// A group other than the daemon's own (root's), to hand the socket.
bool some_other_group(gid_t& gid, std::string& name) {
    for (const char* candidate : {"daemon", "nogroup", "users", "bin", "sys"}) {
        group entry{};
        group* g = nullptr;
        std::vector<char> buffer(16384);
        const int err = ::getgrnam_r(candidate, &entry, buffer.data(), buffer.size(), &g);
        if (err == 0 && g != nullptr && g->gr_gid != ::getegid()) {
            gid = g->gr_gid;
            name = candidate;
            return true;
        }
    }
    return false;
}

// The socket inodes among a process's descriptors.
std::set<std::string> socket_descriptors(pid_t pid) {
    std::set<std::string> inodes;
    for (const auto& fd : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/fd")) {
        std::error_code ec;
        const std::string target = std::filesystem::read_symlink(fd.path(), ec).string();
        if (ec || !target.starts_with("socket:[")) continue;
        inodes.insert(target.substr(8, target.size() - 9));
    }
    return inodes;
}

// The sockets the daemon holds before the tables are read and still holds after: each was
// open while they were read, so it is in one of them (a connection opened or closed meanwhile,
// such as the start-up's readiness probe, is in neither listing or not in both).
TEST(DaemonSecurity, ListensOnNoNetworkPortOnlyOnItsUnixSocket) {
    DaemonOptions o;
    o.shm = true;
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    const std::set<std::string> before = socket_descriptors(d->pid());
    std::set<std::string> network;
    for (const char* t : {"tcp", "tcp6", "udp", "udp6", "raw", "raw6"})
        for (const auto& inode : socket_inodes(std::string("/proc/net/") + t)) network.insert(inode);
    const std::set<std::string> unix_sockets = socket_inodes("/proc/net/unix");
    const std::set<std::string> after = socket_descriptors(d->pid());
    int sockets = 0;
    for (const auto& inode : before) {
        if (after.count(inode) == 0) continue;
        ++sockets;
        EXPECT_EQ(network.count(inode), 0u) << "a network socket: socket:[" << inode << "]";
        EXPECT_EQ(unix_sockets.count(inode), 1u) << "not a Unix socket: socket:[" << inode << "]";
    }
    EXPECT_GE(sockets, 1) << "the listening socket is among its descriptors";
    EXPECT_EQ(d->stop(), 0);
}

TEST(DaemonSecurity, SocketPathThatIsASymlinkIsRefusedAndNotFollowed) {
    TempDir dir;
    const std::string target = dir.file("target.txt");
    const std::string link = dir.file("emu.sock");
    std::ofstream(target) << "keep me\n";
    ASSERT_EQ(::symlink(target.c_str(), link.c_str()), 0);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--socket", link}, out, dir.path()), 1);
    EXPECT_NE(out.find("not a socket"), std::string::npos) << out;
    EXPECT_TRUE(std::filesystem::is_symlink(link)) << "the symlink is kept";
    EXPECT_EQ(first_line(target), "keep me") << "its target is untouched";
}

TEST(DaemonSecurity, DanglingSymlinkAsSocketPathIsRefusedAndNothingCreatedBehindIt) {
    TempDir dir;
    const std::string target = dir.file("elsewhere.sock");
    const std::string link = dir.file("emu.sock");
    ASSERT_EQ(::symlink(target.c_str(), link.c_str()), 0);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--socket", link}, out, dir.path()), 1) << out;
    EXPECT_FALSE(std::filesystem::exists(target)) << "no socket was created through the symlink";
}

TEST(DaemonSecurity, ShmPathThatIsASymlinkIsRefusedAndNotFollowed) {
    TempDir dir;
    const std::string target = dir.file("precious.bin");
    const std::string link = dir.file("emu.shm");
    std::ofstream(target) << "keep me\n";
    ASSERT_EQ(::symlink(target.c_str(), link.c_str()), 0);
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--shm", link}, out, dir.path()), 1);
    EXPECT_TRUE(std::filesystem::is_symlink(link)) << "the symlink is kept";
    EXPECT_EQ(first_line(target), "keep me") << "its target is untouched";
    EXPECT_EQ(std::filesystem::file_size(target), 8u) << "its target was not resized";
}

TEST(DaemonSecurity, GroupOptionHandsSocketAndShmFileToThatGroup) {
    gid_t gid = 0;
    std::string name;
    if (::geteuid() != 0 || !some_other_group(gid, name))
        GTEST_SKIP() << "needs root and a second group to hand the files to";
    DaemonOptions o;
    o.shm = true;
    o.extra_args = {"--group", name};
    auto d = Daemon::start(o);
    ASSERT_NE(d, nullptr);
    for (const std::string& path : {d->socket_path(), d->shm_path()}) {
        struct stat st {};
        ASSERT_EQ(::lstat(path.c_str(), &st), 0) << path;
        EXPECT_EQ(st.st_gid, gid) << path;
        EXPECT_EQ(st.st_mode & 0777, 0660u) << path;
    }
    EXPECT_EQ(d->stop(), 0);
}

TEST(DaemonSecurity, UnknownGroupIsAUsageError) {
    TempDir dir;
    std::string out;
    EXPECT_EQ(apci_test::run_daemon({"--socket", dir.file("emu.sock"), "--group", "no-such-group-apci"}, out,
                                    dir.path()),
              2);
    EXPECT_NE(out.find("no such group"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(dir.file("emu.sock")));
}

}  // namespace
