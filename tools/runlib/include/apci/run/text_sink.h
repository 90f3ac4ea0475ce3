// SPDX-License-Identifier: MIT
// A buffered text sink over a FILE* the caller owns: formats into one buffer and writes it out
// in large pieces, so streaming millions of records costs no allocation per record. The first
// write error is remembered; later output is dropped.
#pragma once

#include <fmt/format.h>

#include <cstdio>
#include <string_view>

namespace apci::run {

class TextSink {
  public:
    static constexpr std::size_t kFlushAt = std::size_t{1} << 16;

    explicit TextSink(std::FILE* out) noexcept : out_(out) {}
    TextSink(const TextSink&) = delete;
    TextSink& operator=(const TextSink&) = delete;
    ~TextSink() { flush(); }

    template <typename... Args>
    void print(fmt::format_string<Args...> format, Args&&... args) {
        fmt::format_to(fmt::appender(buffer_), format, std::forward<Args>(args)...);
        if (buffer_.size() >= kFlushAt) flush();
    }
    void append(std::string_view text) {
        buffer_.append(text);
        if (buffer_.size() >= kFlushAt) flush();
    }
    void put(char c) {
        buffer_.push_back(c);
        if (buffer_.size() >= kFlushAt) flush();
    }
    // Writes the buffer out and flushes the FILE; false if any write failed so far.
    bool flush() noexcept;
    bool failed() const noexcept { return failed_; }

  private:
    std::FILE* out_;
    fmt::memory_buffer buffer_;
    bool failed_ = false;
};

// A JSON number: shortest text that reads back exactly ("102", "-0.5", "1e-05");
// non-finite values (which JSON cannot hold) as null.
void append_json_number(TextSink& sink, double v);
// A JSON string literal with its quotes, escaping what JSON requires.
void append_json_string(TextSink& sink, std::string_view text);

}  // namespace apci::run
