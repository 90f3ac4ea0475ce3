// SPDX-License-Identifier: MIT
#include "apci/run/text_sink.h"

#include <cmath>

namespace apci::run {

bool TextSink::flush() noexcept {
    if (!failed_ && buffer_.size() > 0) {
        if (std::fwrite(buffer_.data(), 1, buffer_.size(), out_) != buffer_.size()) failed_ = true;
    }
    buffer_.clear();
    if (!failed_ && std::fflush(out_) != 0) failed_ = true;
    return !failed_;
}

void append_json_number(TextSink& sink, double v) {
    if (!std::isfinite(v)) {
        sink.append("null");
        return;
    }
    sink.print("{}", v);
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
