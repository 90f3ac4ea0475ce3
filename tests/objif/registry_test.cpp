// SPDX-License-Identifier: MIT
// The registry of running daemons (objif/registry.h), as the host sees it without the emulator:
// where the directory is, what an entry holds, which entries are skipped.
#include "objif/registry.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "other_user.h"

namespace objif {
namespace {

namespace fs = std::filesystem;

// Sets (or unsets) one environment variable for the scope and puts the old value back.
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value != nullptr)
            ::setenv(name, value, 1);
        else
            ::unsetenv(name);
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

  private:
    const char* name_;
    std::optional<std::string> old_;
};

// A fresh directory of this test's own; the registry directory is a child of it, not yet made.
class Registry : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string templ = (fs::temp_directory_path() / "objif-registry-XXXXXX").string();
        ASSERT_NE(::mkdtemp(templ.data()), nullptr);
        root_ = templ;
        dir_ = root_ / "run";
        env_.emplace("APCI_RUNTIME_DIR", dir_.c_str());
    }
    void TearDown() override {
        env_.reset();
        std::error_code ec;
        fs::remove_all(root_, ec);
    }

    // The registry directory as the daemon makes it (mode 0700), with an entry written by hand.
    void write_entry(const std::string& name, const std::string& text) const {
        ::mkdir(dir_.c_str(), 0700);
        std::ofstream(dir_ / name) << text;
    }

    fs::path root_;
    fs::path dir_;
    std::optional<ScopedEnv> env_;
};

// A pid no process has: a child that has exited and been reaped.
pid_t gone_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
}

TEST(RegistryDir, RuntimeDirFirstThenXdgThenTmp) {
    {
        ScopedEnv apci("APCI_RUNTIME_DIR", "/somewhere/apci-run");
        ScopedEnv xdg("XDG_RUNTIME_DIR", "/run/user/4242");
        EXPECT_EQ(registry_dir(), "/somewhere/apci-run");
    }
    {
        ScopedEnv apci("APCI_RUNTIME_DIR", "");  // empty counts as unset
        ScopedEnv xdg("XDG_RUNTIME_DIR", "/run/user/4242");
        EXPECT_EQ(registry_dir(), "/run/user/4242/apci");
    }
    {
        ScopedEnv apci("APCI_RUNTIME_DIR", nullptr);
        ScopedEnv xdg("XDG_RUNTIME_DIR", nullptr);
        EXPECT_EQ(registry_dir(), "/tmp/apci-" + std::to_string(::getuid()));
    }
}

TEST_F(Registry, MissingDirectoryIsAnEmptyList) {
    std::vector<RegisteredDaemon> found;
    std::string why;
    EXPECT_TRUE(registered_daemons(found, why)) << why;
    EXPECT_TRUE(found.empty());
    EXPECT_FALSE(fs::exists(dir_));  // reading creates nothing
}

TEST_F(Registry, AnEntryIsListedWithItsPathsUntilItIsRemoved) {
    std::string why;
    const RegisteredDaemon self{::getpid(), "/run/a b.sock", "/dev/shm/board"};
    ASSERT_TRUE(register_daemon(self, why)) << why;
    EXPECT_EQ(fs::status(dir_).permissions() & fs::perms::all, fs::perms::owner_all);

    std::vector<RegisteredDaemon> found;
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    ASSERT_EQ(found.size(), 1U);
    EXPECT_EQ(found[0].pid, self.pid);
    EXPECT_EQ(found[0].socket, "/run/a b.sock");  // a path may hold spaces
    EXPECT_EQ(found[0].shm, "/dev/shm/board");

    unregister_daemon(self.pid);
    found.clear();
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    EXPECT_TRUE(found.empty());
    EXPECT_TRUE(fs::is_empty(dir_));  // no temporary file left behind either
}

TEST_F(Registry, ADaemonWithoutShmHasAnEmptyShm) {
    std::string why;
    ASSERT_TRUE(register_daemon({::getpid(), "/run/x.sock", ""}, why)) << why;
    std::vector<RegisteredDaemon> found;
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    ASSERT_EQ(found.size(), 1U);
    EXPECT_EQ(found[0].socket, "/run/x.sock");
    EXPECT_EQ(found[0].shm, "");
    unregister_daemon(::getpid());
}

TEST_F(Registry, EntriesOfGoneProcessesAndOtherFilesAreSkipped) {
    const pid_t gone = gone_pid();
    write_entry("rwmos-emu." + std::to_string(gone), "socket /run/gone.sock\n");
    write_entry("rwmos-emu." + std::to_string(::getpid()) + ".tmp", "socket /run/torn.sock\n");
    write_entry("rwmos-emu.12x", "socket /run/bad.sock\n");
    write_entry("rwmos-emu.", "socket /run/none.sock\n");
    write_entry("other." + std::to_string(::getpid()), "socket /run/other.sock\n");
    write_entry("rwmos-emu." + std::to_string(::getpid()), "socket /run/live.sock\n");

    std::vector<RegisteredDaemon> found;
    std::string why;
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    ASSERT_EQ(found.size(), 1U);
    EXPECT_EQ(found[0].pid, ::getpid());
    EXPECT_EQ(found[0].socket, "/run/live.sock");
}

TEST_F(Registry, ADirectoryThatCannotBeMadeIsNamed) {
    // The registry directory's parent is a file.
    std::ofstream(root_ / "file") << "x";
    ScopedEnv apci("APCI_RUNTIME_DIR", (root_ / "file" / "run").c_str());
    std::string why;
    EXPECT_FALSE(register_daemon({::getpid(), "/run/x.sock", ""}, why));
    EXPECT_NE(why.find("registry directory " + (root_ / "file" / "run").string()),
              std::string::npos)
        << why;

    std::vector<RegisteredDaemon> found;
    why.clear();
    EXPECT_FALSE(registered_daemons(found, why));
    EXPECT_NE(why.find("registry directory"), std::string::npos) << why;
    EXPECT_TRUE(found.empty());
}

// The file names of entries that name no process: pid 0 (kill(0, 0) asks this process's group,
// which always answers), negative pids (kill(-N, 0) asks a process group, kill(-1, 0) every
// process), and names that are not the plain decimal form the daemon writes. None is listed,
// even next to a live process's own entry and with this process's pid in them.
TEST_F(Registry, EntriesOfPidZeroOrANegativePidAreNeverListed) {
    const std::string own = std::to_string(::getpid());
    const std::string group = std::to_string(::getpgrp());
    for (const std::string& pid :
         {std::string("0"), std::string("-0"), std::string("-1"), "-" + own, "-" + group, "0" + own,
          "+" + own, " " + own, own + " ", std::string("2147483648"), std::string("-2147483648"),
          std::string("4294967295")})
        write_entry("rwmos-emu." + pid, "socket /run/pid" + pid + ".sock\n");
    write_entry("rwmos-emu." + own, "socket /run/live.sock\n");

    std::vector<RegisteredDaemon> found;
    std::string why;
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    ASSERT_EQ(found.size(), 1U);
    EXPECT_EQ(found[0].pid, ::getpid());
    EXPECT_EQ(found[0].socket, "/run/live.sock");
}

// A path is one line of the entry whatever it holds: a socket path with a line end and
// "shm FILE" after it does not make a second line (it made the entry name FILE as the daemon's
// shared-memory file), and a backslash or a control character comes back as it went in.
TEST_F(Registry, APathWithALineEndOrABackslashComesBackWhole) {
    const std::string socket = "/run/x\nshm /home/user/precious.txt";
    const std::string shm = std::string("/dev/shm/a\\nb\\\\c\x01\x7f\r\t d");
    std::string why;
    ASSERT_TRUE(register_daemon({::getpid(), socket, ""}, why)) << why;
    std::vector<RegisteredDaemon> found;
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    ASSERT_EQ(found.size(), 1U);
    EXPECT_EQ(found[0].socket, socket);
    EXPECT_EQ(found[0].shm, "");

    ASSERT_TRUE(register_daemon({::getpid(), "/run/y.sock", shm}, why)) << why;
    found.clear();
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    ASSERT_EQ(found.size(), 1U);
    EXPECT_EQ(found[0].socket, "/run/y.sock");
    EXPECT_EQ(found[0].shm, shm);
    unregister_daemon(::getpid());
}

TEST(RegistryEscape, EveryByteRoundTripsAndOnlyWrittenEscapesAreRead) {
    std::string all;
    for (int c = 1; c < 256; ++c) all += static_cast<char>(c);
    const std::string escaped = escape_registry_path(all);
    EXPECT_EQ(escaped.find('\n'), std::string::npos);
    std::string back;
    ASSERT_TRUE(unescape_registry_path(escaped, back));
    EXPECT_EQ(back, all);
    for (const char* bad : {"\\", "a\\q", "\\x4", "\\x41", "\\x0a", "\\xzz", "a\nb", "a\rb"})
        EXPECT_FALSE(unescape_registry_path(bad, back)) << bad;
}

// The daemon registers absolute paths (a relative one means nothing to a reader elsewhere,
// and `apcictl list` printed it as an unusable URI); register_daemon refuses a relative one.
TEST_F(Registry, ARelativePathIsRefused) {
    std::string why;
    EXPECT_FALSE(register_daemon({::getpid(), "emu.sock", ""}, why));
    EXPECT_NE(why.find("'emu.sock' is not absolute"), std::string::npos) << why;
    EXPECT_FALSE(register_daemon({::getpid(), "/run/emu.sock", "board.dpram"}, why));
    EXPECT_NE(why.find("'board.dpram' is not absolute"), std::string::npos) << why;
    EXPECT_FALSE(fs::exists(dir_ / ("rwmos-emu." + std::to_string(::getpid()))));
    // An entry written by another program with a relative path is skipped.
    write_entry("rwmos-emu." + std::to_string(::getpid()), "socket emu.sock\n");
    std::vector<RegisteredDaemon> found;
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    EXPECT_TRUE(found.empty());
}

// A temporary entry name that is already there (a symbolic link to a file of the user's, left
// in the directory) is replaced, never written through.
TEST_F(Registry, ATemporaryNameThatIsASymlinkIsReplacedNotFollowed) {
    const fs::path victim = root_ / "victim.txt";
    std::ofstream(victim) << "keep me";
    ::mkdir(dir_.c_str(), 0700);
    const fs::path tmp = dir_ / ("rwmos-emu." + std::to_string(::getpid()) + ".tmp");
    fs::create_symlink(victim, tmp);
    std::string why;
    ASSERT_TRUE(register_daemon({::getpid(), "/run/x.sock", ""}, why)) << why;
    std::ifstream in(victim);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "keep me");
    EXPECT_FALSE(fs::exists(fs::symlink_status(tmp)));
    unregister_daemon(::getpid());
}

// A directory of ours that others may enter, and a symbolic link in its place (even to a
// private directory of ours), are refused: nothing is written there, nothing read from it.
TEST_F(Registry, ADirectoryOpenToOthersOrASymlinkIsRefused) {
    write_entry("rwmos-emu." + std::to_string(::getpid()), "socket /run/planted.sock\n");
    ASSERT_EQ(::chmod(dir_.c_str(), 0777), 0);
    std::string why;
    EXPECT_FALSE(register_daemon({::getpid(), "/run/x.sock", ""}, why));
    EXPECT_NE(why.find("has mode 0777"), std::string::npos) << why;
    std::vector<RegisteredDaemon> found;
    EXPECT_FALSE(registered_daemons(found, why));
    EXPECT_NE(why.find("has mode 0777"), std::string::npos) << why;
    EXPECT_TRUE(found.empty());
    ASSERT_EQ(::chmod(dir_.c_str(), 0710), 0);  // group may only enter: still not private
    EXPECT_FALSE(registered_daemons(found, why));
    EXPECT_TRUE(found.empty());

    ASSERT_EQ(::chmod(dir_.c_str(), 0700), 0);
    const fs::path link = root_ / "link";
    fs::create_directory_symlink(dir_, link);
    ScopedEnv apci("APCI_RUNTIME_DIR", link.c_str());
    EXPECT_FALSE(register_daemon({::getpid(), "/run/x.sock", ""}, why));
    EXPECT_NE(why.find("is a symbolic link"), std::string::npos) << why;
    EXPECT_FALSE(registered_daemons(found, why));
    EXPECT_NE(why.find("is a symbolic link"), std::string::npos) << why;
    EXPECT_TRUE(found.empty());
}

// The attack of the /tmp fallback: another user makes the registry directory first (mode 0777,
// as anyone may in /tmp), links the daemon's temporary entry name to a file of the daemon's
// user and plants an entry naming a socket of theirs. The daemon's user refuses the directory:
// the linked file keeps its contents, nothing is created there, and the planted entry is not
// listed. The directory's owner is someone else for real (made by user nobody).
TEST_F(Registry, ARegistryDirectoryMadeByAnotherUserIsRefusedAndNothingWrittenThroughIt) {
    if (!test_support::can_act_as_other_user()) GTEST_SKIP() << "needs root to act as another user";
    ASSERT_EQ(::chmod(root_.c_str(), 01777), 0);  // a shared directory like /tmp
    const fs::path victim = root_ / "victim.txt";
    std::ofstream(victim) << "the user's own file";
    const std::string pid = std::to_string(::getpid());
    const fs::path dir = dir_;
    ASSERT_TRUE(test_support::as_other_user([&] {
        if (::mkdir(dir.c_str(), 0777) != 0 || ::chmod(dir.c_str(), 0777) != 0) return false;
        if (::symlink(victim.c_str(), (dir / ("rwmos-emu." + pid + ".tmp")).c_str()) != 0)
            return false;
        const int fd = ::open((dir / ("rwmos-emu." + pid)).c_str(),
                              O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) return false;
        const std::string planted = "socket /tmp/attacker.sock\n";
        const bool ok =
            ::write(fd, planted.data(), planted.size()) == static_cast<ssize_t>(planted.size());
        return ::close(fd) == 0 && ok;
    }));
    struct stat st {};
    ASSERT_EQ(::lstat(dir_.c_str(), &st), 0);
    ASSERT_EQ(st.st_uid, test_support::kOtherUid);

    std::string why;
    EXPECT_FALSE(register_daemon({::getpid(), "/run/x.sock", "/dev/shm/board"}, why));
    EXPECT_NE(why.find("belongs to uid 65534"), std::string::npos) << why;
    std::ifstream in(victim);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "the user's own file");
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++files;
    EXPECT_EQ(files, 2U);  // the link and the planted entry, nothing else

    std::vector<RegisteredDaemon> found;
    EXPECT_FALSE(registered_daemons(found, why));
    EXPECT_NE(why.find("belongs to uid 65534"), std::string::npos) << why;
    EXPECT_TRUE(found.empty());
    unregister_daemon(::getpid());  // removes nothing there
    EXPECT_TRUE(fs::exists(dir_ / ("rwmos-emu." + pid)));
}

// The other side: user nobody, whose registry directory root made first, refuses it too; and an
// entry file of another user's inside one's own directory is not read.
TEST_F(Registry, ADaemonOfAnotherUserRefusesADirectoryThatIsNotItsOwn) {
    if (!test_support::can_act_as_other_user()) GTEST_SKIP() << "needs root to act as another user";
    ASSERT_EQ(::chmod(root_.c_str(), 0755), 0);
    ASSERT_EQ(::mkdir(dir_.c_str(), 0700), 0);
    EXPECT_TRUE(test_support::as_other_user([&] {
        std::string why;
        std::vector<RegisteredDaemon> found;
        return !register_daemon({::getpid(), "/run/x.sock", ""}, why) &&
               why.find("belongs to uid 0") != std::string::npos &&
               !registered_daemons(found, why) && found.empty();
    }));
    // Root's directory with an entry file that belongs to nobody: skipped.
    write_entry("rwmos-emu." + std::to_string(::getpid()), "socket /run/nobody.sock\n");
    ASSERT_EQ(::chown((dir_ / ("rwmos-emu." + std::to_string(::getpid()))).c_str(),
                      test_support::kOtherUid, test_support::kOtherGid),
              0);
    std::vector<RegisteredDaemon> found;
    std::string why;
    ASSERT_TRUE(registered_daemons(found, why)) << why;
    EXPECT_TRUE(found.empty());
    // Nobody's own registry directory (made by nobody, 0700) is used by nobody.
    const fs::path own = root_ / "nobody-run";
    ASSERT_EQ(::chmod(root_.c_str(), 01777), 0);
    ScopedEnv apci("APCI_RUNTIME_DIR", own.c_str());
    EXPECT_TRUE(test_support::as_other_user([&] {
        std::string why;
        std::vector<RegisteredDaemon> found;
        if (!register_daemon({::getpid(), "/run/x.sock", ""}, why)) return false;
        const bool listed =
            registered_daemons(found, why) && found.size() == 1 && found[0].socket == "/run/x.sock";
        unregister_daemon(::getpid());
        return listed;
    }));
}

}  // namespace
}  // namespace objif
