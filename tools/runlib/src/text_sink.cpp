// SPDX-License-Identifier: MIT
#include "apci/run/text_sink.h"

#include <charconv>
#include <cmath>

#include "ready_pages.h"

namespace apci::run {

namespace {

// A block of a huge page's size (map_block), its first kCapacity bytes made ready.
char* new_buffer() {
    static_assert(TextSink::kCapacity <= detail::kHugePage);
    detail::MappedBlock block = detail::map_block(detail::kHugePage);
    detail::make_ready(block.get(), TextSink::kCapacity);
    return reinterpret_cast<char*>(block.release());
}

}  // namespace

TextSink::TextSink(std::FILE* out) : out_(out), buffer_(new_buffer()) {}

void TextSink::Release::operator()(char* buffer) const noexcept {
    detail::Unmap{detail::kHugePage}(reinterpret_cast<std::byte*>(buffer));
}

void TextSink::write_out() noexcept {
    if (!failed_ && used_ > 0 && std::fwrite(buffer_.get(), 1, used_, out_) != used_)
        failed_ = true;
    used_ = 0;
}

void TextSink::write_through(std::string_view text) noexcept {
    if (!failed_ && std::fwrite(text.data(), 1, text.size(), out_) != text.size()) failed_ = true;
}

bool TextSink::flush() noexcept {
    write_out();
    if (!failed_ && std::fflush(out_) != 0) failed_ = true;
    return !failed_;
}

void append_json_number(TextSink& sink, double v) {
    if (!std::isfinite(v)) {
        sink.append("null");
        return;
    }
    // std::to_chars without a format is the shortest text that reads back exactly; it writes
    // straight into a small array, with no format string to parse (the segments of a long run
    // are mostly numbers).
    char text[32];
    // Whole numbers (common in NC coordinates) as integers: the same value, and much cheaper
    // than the shortest-float search. -0 keeps its sign.
    constexpr double kExactInteger = 1e15;
    if (v == std::trunc(v) && std::abs(v) < kExactInteger && !(v == 0.0 && std::signbit(v))) {
        append_integer(sink, static_cast<std::int64_t>(v));
        return;
    }
    const auto r = std::to_chars(text, text + sizeof text, v);
    sink.append(std::string_view(text, static_cast<std::size_t>(r.ptr - text)));
}

void append_integer(TextSink& sink, std::int64_t v) {
    char text[24];
    const auto r = std::to_chars(text, text + sizeof text, v);
    sink.append(std::string_view(text, static_cast<std::size_t>(r.ptr - text)));
}

void append_json_string(TextSink& sink, std::string_view text) {
    sink.put('"');
    for (const char c : text) {
        switch (c) {
            case '"':
                sink.append("\\\"");
                break;
            case '\\':
                sink.append("\\\\");
                break;
            case '\n':
                sink.append("\\n");
                break;
            case '\r':
                sink.append("\\r");
                break;
            case '\t':
                sink.append("\\t");
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    sink.print("\\u{:04x}", static_cast<unsigned>(c));
                } else {
                    sink.put(c);
                }
        }
    }
    sink.put('"');
}

}  // namespace apci::run
