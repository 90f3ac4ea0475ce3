// SPDX-License-Identifier: MIT
// The registry of running daemons (objif/registry.h), as the host sees it without the emulator:
// where the directory is, what an entry holds, which entries are skipped.
#include "objif/registry.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

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

    void write_entry(const std::string& name, const std::string& text) const {
        fs::create_directories(dir_);
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

}  // namespace
}  // namespace objif
