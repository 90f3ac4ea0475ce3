// SPDX-License-Identifier: MIT
// A FILE in memory for the run writers' tests: text() gives what was written so far.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace apci_test {

class MemoryFile {
  public:
    MemoryFile() : file_(open_memstream(&data_, &size_)) {}
    ~MemoryFile() {
        if (file_ != nullptr) std::fclose(file_);
        std::free(data_);
    }
    MemoryFile(const MemoryFile&) = delete;
    MemoryFile& operator=(const MemoryFile&) = delete;
    std::FILE* get() const { return file_; }
    std::string text() {
        std::fflush(file_);
        return std::string(data_, size_);
    }
    // The same without a copy: valid until the next write.
    std::string_view view() {
        std::fflush(file_);
        return std::string_view(data_, size_);
    }

  private:
    char* data_ = nullptr;
    std::size_t size_ = 0;
    std::FILE* file_;
};

}  // namespace apci_test
