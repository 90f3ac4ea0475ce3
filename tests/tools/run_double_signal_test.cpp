// SPDX-License-Identifier: MIT
// `apcictl run` ended by a signal that comes twice in quick succession, as `timeout` sends it
// (to the process, then to its process group): the first removes the temporary files of the
// outputs, and the second must not end the process before it has (docs/apcictl.md, "Outputs").
// The run's other threads may take the second signal while the first is being handled: with
// the default action put back at once (SA_RESETHAND) they ended the process mid-cleanup and
// left hidden files (.out.json.apcictl-...) behind.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "scratch_dir.h"
#include "text.h"

namespace {

using test_support::names_in;

TEST(RunDoubleSignal, SecondSignalWaitsForTheTemporaryFilesToBeRemoved) {
    const test_support::ScratchDir scratch("run_double_signal_");
    const std::string& root = scratch.path();
    ASSERT_FALSE(root.empty());
    std::ofstream(root + "/long.nc") << "N10 G1 X1000 F60\nM30\n";  // a minute of cycles
    // Tries: the race is a matter of microseconds (it was lost in about 2 of 60 tries).
    constexpr int kTries = 60;
    int left_behind = 0;
    for (int i = 0; i < kTries; ++i) {
        const pid_t pid = ::fork();
        if (pid == 0) {
            if (::chdir(root.c_str()) != 0) ::_exit(126);
            const int null = ::open("/dev/null", O_RDWR);
            ::dup2(null, 0);
            ::dup2(null, 1);
            ::dup2(null, 2);
            for (int sig : {SIGTERM, SIGINT, SIGHUP}) std::signal(sig, SIG_DFL);
            ::execl(APCICTL_PATH, APCICTL_PATH, "run", "long.nc", "--json", "out.json", "--csv",
                    "out.csv", "--svg", "out.svg", static_cast<char*>(nullptr));
            ::_exit(127);
        }
        // Wait until the temporary files are there (the run is under way), then SIGTERM twice.
        bool under_way = false;
        for (int k = 0; k < 2000 && !under_way; ++k) {
            int hidden = 0;
            for (const std::string& name : names_in(root)) hidden += name[0] == '.';
            under_way = hidden >= 3;
            if (!under_way) std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
        ASSERT_TRUE(under_way) << "try " << i;
        // A little later each try, so the signals meet the run at different points.
        std::this_thread::sleep_for(std::chrono::microseconds(200 * (i % 10)));
        ::kill(pid, SIGTERM);
        ::kill(pid, SIGTERM);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "try " << i;
        const auto names = names_in(root);
        if (names != std::set<std::string>{"long.nc"}) {
            ++left_behind;
            ADD_FAILURE() << "try " << i << " left " << names.size() - 1 << " file(s), e.g. "
                          << *names.begin();
            for (const std::string& name : names)
                if (name != "long.nc") ::unlink((root + "/" + name).c_str());
        }
    }
    EXPECT_EQ(left_behind, 0) << "of " << kTries << " tries";
}

}  // namespace
