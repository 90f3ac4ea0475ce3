// SPDX-License-Identifier: MIT
// A test fixture with a scratch directory of its own: the test's files are named in it and
// written into it, and it is removed with all it holds when the test ends.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "scratch_dir.h"
#include "text.h"

namespace test_support {

class ScratchTest : public ::testing::Test {
  protected:
    // prefix: the directory's name before its six random characters (it names the test's files
    // in $TMPDIR should one be left behind).
    explicit ScratchTest(const std::string& prefix) : scratch_(prefix) {}

    void SetUp() override { ASSERT_FALSE(dir().empty()) << "no scratch directory"; }

    // The test's own directory.
    const std::string& dir() const { return scratch_.path(); }
    // The path of `name` in it.
    std::string path(const std::string& name) const { return scratch_.file(name); }
    // Writes `text` to the file `name` in it; returns the file's path.
    std::string write(const std::string& name, const std::string& text) const {
        return write_text(path(name), text);
    }

  private:
    ScratchDir scratch_;
};

}  // namespace test_support
