// SPDX-License-Identifier: MIT
// A buffered text sink over a FILE* the caller owns: collects text in one fixed buffer and
// writes it out in large pieces, so streaming millions of records costs no allocation per
// record. The first write error is remembered; later output is dropped.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string_view>

namespace apci::run {

class TextSink {
  public:
    // 1 MiB: a 27 MB JSON in 26 write(2) calls instead of 412 (docs/performance.md).
    static constexpr std::size_t kCapacity = std::size_t{1} << 20;

    // The buffer is a block of its own, its first MiB made ready at once (the run library's
    // ready_pages.h): a long output writes it without a page fault per 4 KiB
    // (docs/performance.md, "Memory made ready before it is written").
    explicit TextSink(std::FILE* out);
    TextSink(const TextSink&) = delete;
    TextSink& operator=(const TextSink&) = delete;
    ~TextSink() { flush(); }

    // Formatted text (fmt syntax), for the parts written once or rarely.
    template <typename... Args>
    void print(fmt::format_string<Args...> format, Args&&... args) {
        fmt::memory_buffer text;
        fmt::format_to(fmt::appender(text), format, std::forward<Args>(args)...);
        append(std::string_view(text.data(), text.size()));
    }
    // Plain text: a copy into the buffer (the per-record path).
    void append(std::string_view text) {
        if (text.size() > kCapacity - used_) {
            write_out();
            if (text.size() > kCapacity) {
                write_through(text);
                return;
            }
        }
        std::memcpy(buffer_.get() + used_, text.data(), text.size());
        used_ += text.size();
    }
    void put(char c) {
        if (used_ == kCapacity) write_out();
        buffer_[used_++] = c;
    }
    // Room for up to `size` characters (at most kCapacity) at the end of the text: the caller
    // writes them in place and hands back their end with commit(). One bounds check for a
    // whole record instead of one per piece.
    char* reserve(std::size_t size) {
        if (size > kCapacity - used_) write_out();
        return buffer_.get() + used_;
    }
    void commit(const char* end) noexcept { used_ = static_cast<std::size_t>(end - buffer_.get()); }
    // Writes the buffer out and flushes the FILE; false if any write failed so far.
    bool flush() noexcept;
    bool failed() const noexcept { return failed_; }

  private:
    void write_out() noexcept;
    void write_through(std::string_view text) noexcept;

    struct Release {
        void operator()(char* buffer) const noexcept;
    };
    std::FILE* out_;
    std::unique_ptr<char[], Release> buffer_;
    std::size_t used_ = 0;
    bool failed_ = false;
};

// A JSON number: shortest text that reads back exactly ("102", "-0.5", "1e-05");
// non-finite values (which JSON cannot hold) as null.
void append_json_number(TextSink& sink, double v);
// A whole number in decimal.
void append_integer(TextSink& sink, std::int64_t v);
// A JSON string literal with its quotes, escaping what JSON requires.
void append_json_string(TextSink& sink, std::string_view text);

}  // namespace apci::run
