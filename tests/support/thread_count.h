// SPDX-License-Identifier: MIT
// How many threads the test process runs, for tests that no thread outlives what started it.
#pragma once

#include <dirent.h>

#include <thread>

namespace apci::test {

// The threads of this process (/proc/self/task); -1 if it cannot be read.
inline int thread_count() {
    DIR* d = ::opendir("/proc/self/task");
    if (d == nullptr) return -1;
    int n = 0;
    while (const dirent* e = ::readdir(d))
        if (e->d_name[0] != '.') ++n;
    ::closedir(d);
    return n;
}

// The threads before a test's own: a thread is started and joined first, so a helper thread a
// sanitizer starts with the process's first thread (ThreadSanitizer's) is among them.
inline int baseline_thread_count() {
    std::thread([] {}).join();
    return thread_count();
}

}  // namespace apci::test
