// SPDX-License-Identifier: MIT
// Acting as another user in a test. The suite runs as root, where every file a test makes is
// root's own, so a check "is this file ours?" would pass whatever it compared. A forked child
// that has given up root for user nobody (uid and gid 65534, no supplementary groups) makes the
// files another user would make, or runs the code under test as that user. Without root the
// test cannot do this and is skipped.
#pragma once

#include <grp.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

namespace test_support {

inline constexpr uid_t kOtherUid = 65534;  // nobody
inline constexpr gid_t kOtherGid = 65534;  // nogroup

// Whether this process may act as another user (it is root).
inline bool can_act_as_other_user() {
    return ::geteuid() == 0;
}

// Runs `body` in a forked child as user nobody; returns its result (true: it passed), false
// also when the child could not become nobody or died. The child shares nothing with the test
// but what fork copied: it reports through its exit code only.
inline bool as_other_user(const std::function<bool()>& body) {
    const pid_t child = ::fork();
    if (child < 0) return false;
    if (child == 0) {
        if (::setgroups(0, nullptr) != 0 || ::setresgid(kOtherGid, kOtherGid, kOtherGid) != 0 ||
            ::setresuid(kOtherUid, kOtherUid, kOtherUid) != 0 || ::geteuid() != kOtherUid)
            ::_exit(3);
        ::_exit(body() ? 0 : 1);
    }
    int status = 0;
    if (::waitpid(child, &status, 0) != child) return false;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace test_support
