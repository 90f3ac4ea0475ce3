// SPDX-License-Identifier: MIT
// Small helpers on text and files for the tests: a substring test, a whole file as text, a file
// written from text, the names in a directory.
#pragma once

#include <dirent.h>
#include <sys/stat.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <string_view>

namespace test_support {

// Whether `part` occurs in `text`.
inline bool contains(std::string_view text, std::string_view part) {
    return text.find(part) != std::string_view::npos;
}

// The whole file as text; empty when it cannot be read.
inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Writes `text` to `path` (created or truncated); returns `path`.
inline std::string write_text(const std::string& path, std::string_view text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// Whether something (a file, a directory, a dangling link) is at `path`.
inline bool path_exists(const std::string& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0;
}

// The names in a directory, without "." and ".."; empty when it cannot be read.
inline std::set<std::string> names_in(const std::string& dir) {
    std::set<std::string> names;
    DIR* d = ::opendir(dir.c_str());
    if (d == nullptr) return names;
    while (const dirent* e = ::readdir(d)) {
        const std::string name = e->d_name;
        if (name != "." && name != "..") names.insert(name);
    }
    ::closedir(d);
    return names;
}

}  // namespace test_support
