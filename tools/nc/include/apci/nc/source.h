// SPDX-License-Identifier: MIT
// Line-by-line reading of an NC program or tool file with flat memory: one fixed buffer, no
// per-line allocation, so a program of any length is read in constant space.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "apci/nc/diagnostic.h"

namespace apci::nc {

class LineSource {
  public:
    // Longest accepted line in bytes (without its line end); longer lines are an error, so that
    // memory stays bounded whatever the input.
    static constexpr std::size_t kMaxLineLength = std::size_t{64} * 1024;
    // UTF-8's byte-order mark: at the start of a source it is left out (next()).
    static constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

    // Opens a file for reading; the diagnostic names the path and the system's reason.
    static Result<LineSource> open_file(const std::string& path);
    // Reads from text held by the caller (it must outlive the source); nothing is copied.
    static LineSource from_text(std::string_view text, std::string name);

    LineSource(LineSource&& other) noexcept;
    LineSource& operator=(LineSource&& other) noexcept;
    LineSource(const LineSource&) = delete;
    LineSource& operator=(const LineSource&) = delete;
    ~LineSource();

    enum class Read { kLine, kEnd, kError };
    // The next line without its "\n" or "\r\n". The view stays valid until the next call.
    // kError (I/O error, line too long) fills err; the source then stays in error.
    Read next(std::string_view& line, Diagnostic& err);

    // 1-based number of the line last returned (0 before the first).
    std::uint64_t line_number() const noexcept { return line_number_; }

    // Where the next line starts, to come back to it ($FOR loops replay their body): the byte
    // offset in the file or text and the number of the line before it. Memory stays flat: a
    // position is two numbers; seek() reuses the buffer when the place is still in it and
    // re-reads the file from there otherwise.
    struct Position {
        std::uint64_t offset = 0;
        std::uint64_t line_number = 0;
    };
    Position tell() const noexcept { return {base_ + pos_, line_number_}; }
    // Back to a position tell() gave on this source. False with err when the file cannot be
    // positioned (the source then stays in error).
    bool seek(const Position& p, Diagnostic& err);
    const std::string& name() const noexcept { return name_; }

  private:
    LineSource(std::string name, std::FILE* file);
    LineSource(std::string name, std::string_view text);
    bool refill(Diagnostic& err);  // keeps [pos_, end_) and reads more behind it

    std::string name_;
    std::FILE* file_ = nullptr;
    std::unique_ptr<char[]> storage_;  // file mode only: 2 * kMaxLineLength bytes
    const char* data_ = nullptr;       // start of the buffered bytes (storage_ or caller's text)
    std::size_t pos_ = 0;              // next unread byte
    std::size_t end_ = 0;              // one past the last buffered byte
    std::uint64_t base_ = 0;           // file offset of data_[0]
    bool eof_ = false;                 // nothing more to read behind end_
    bool failed_ = false;
    std::uint64_t line_number_ = 0;
};

}  // namespace apci::nc
