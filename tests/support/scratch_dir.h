// SPDX-License-Identifier: MIT
// A directory of a test's own under $TMPDIR (or /tmp), removed with all it holds when the test
// ends. `dir` is empty when it could not be made.
#pragma once

#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace test_support {

struct ScratchDir {
    std::string dir;
    // prefix: the directory's name before the six random characters.
    explicit ScratchDir(const std::string& prefix) {
        const char* tmp = std::getenv("TMPDIR");
        std::string templ =
            std::string(tmp != nullptr && *tmp ? tmp : "/tmp") + "/" + prefix + "XXXXXX";
        if (::mkdtemp(templ.data()) != nullptr) dir = templ;
    }
    ~ScratchDir() {
        std::error_code ignored;
        if (!dir.empty()) std::filesystem::remove_all(dir, ignored);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
};

}  // namespace test_support
