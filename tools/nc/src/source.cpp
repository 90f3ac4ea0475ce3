// SPDX-License-Identifier: MIT
#include "apci/nc/source.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>

namespace apci::nc {

namespace {
constexpr std::size_t kBufferSize = 2 * LineSource::kMaxLineLength;
}

Result<LineSource> LineSource::open_file(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) {
        Diagnostic d;
        d.kind = ErrorKind::kIo;
        d.file = path;
        d.message = fmt::format("cannot open: {}", std::strerror(errno));
        return d;
    }
    // Our own buffer does the buffering; a second one inside stdio would only copy twice.
    std::setvbuf(f, nullptr, _IONBF, 0);
    return LineSource(path, f);
}

LineSource LineSource::from_text(std::string_view text, std::string name) {
    return LineSource(std::move(name), text);
}

LineSource::LineSource(std::string name, std::FILE* file)
    : name_(std::move(name)), file_(file), storage_(new char[kBufferSize]) {
    data_ = storage_.get();
}

LineSource::LineSource(std::string name, std::string_view text)
    : name_(std::move(name)), data_(text.data()), end_(text.size()), eof_(true) {}

LineSource::LineSource(LineSource&& o) noexcept
    : name_(std::move(o.name_)),
      file_(o.file_),
      storage_(std::move(o.storage_)),
      data_(o.data_),
      pos_(o.pos_),
      end_(o.end_),
      base_(o.base_),
      eof_(o.eof_),
      failed_(o.failed_),
      line_number_(o.line_number_) {
    o.file_ = nullptr;
}

LineSource& LineSource::operator=(LineSource&& o) noexcept {
    if (this != &o) {
        if (file_ != nullptr) std::fclose(file_);
        name_ = std::move(o.name_);
        file_ = o.file_;
        storage_ = std::move(o.storage_);
        data_ = o.data_;
        pos_ = o.pos_;
        end_ = o.end_;
        base_ = o.base_;
        eof_ = o.eof_;
        failed_ = o.failed_;
        line_number_ = o.line_number_;
        o.file_ = nullptr;
    }
    return *this;
}

LineSource::~LineSource() {
    if (file_ != nullptr) std::fclose(file_);
}

bool LineSource::refill(Diagnostic& err) {
    const std::size_t kept = end_ - pos_;
    char* buf = storage_.get();
    if (pos_ != 0 && kept != 0) std::memmove(buf, buf + pos_, kept);
    base_ += pos_;
    pos_ = 0;
    end_ = kept;
    while (end_ < kBufferSize) {
        const std::size_t got = std::fread(buf + end_, 1, kBufferSize - end_, file_);
        end_ += got;
        if (got == 0) {
            if (std::ferror(file_) != 0) {
                err.kind = ErrorKind::kIo;
                err.file = name_;
                err.line = line_number_ + 1;
                err.column = 1;
                err.message = fmt::format("read error: {}", std::strerror(errno));
                return false;
            }
            eof_ = true;
            break;
        }
        // One read is enough when it brought a line end; avoids waiting on pipes.
        if (std::memchr(buf + end_ - got, '\n', got) != nullptr) break;
    }
    return true;
}

LineSource::Read LineSource::next(std::string_view& line, Diagnostic& err) {
    if (failed_) return Read::kError;
    for (;;) {
        const char* start = data_ + pos_;
        const std::size_t avail = end_ - pos_;
        // A UTF-8 byte-order mark at the very start (editors on Windows and CAM systems write
        // one) is no character of the first line: left out, and not counted in its length.
        const std::size_t mark = base_ + pos_ == 0 && avail >= kByteOrderMark.size() &&
                                         std::string_view(start, kByteOrderMark.size()) ==
                                             kByteOrderMark
                                     ? kByteOrderMark.size()
                                     : 0;
        const auto* nl = static_cast<const char*>(std::memchr(start, '\n', avail));
        std::size_t len = 0;
        bool have_line = false;
        if (nl != nullptr) {
            len = static_cast<std::size_t>(nl - start);
            pos_ += len + 1;
            have_line = true;
        } else if (eof_) {
            if (avail == 0) return Read::kEnd;
            len = avail;
            pos_ = end_;
            have_line = true;
        }
        if (have_line) {
            if (len > 0 && start[len - 1] == '\r') --len;
            ++line_number_;
            if (len - mark > kMaxLineLength) break;
            line = std::string_view(start + mark, len - mark);
            return Read::kLine;
        }
        // No line end yet: more than the bound is a line too long, but a line of exactly the
        // bound may end in "\r" with its "\n" not read yet (the buffer's last byte), and the
        // first line may begin with a byte-order mark.
        if (avail > kMaxLineLength + 1 + mark) {
            ++line_number_;
            break;
        }
        if (!refill(err)) {
            failed_ = true;
            return Read::kError;
        }
    }
    failed_ = true;
    err.kind = ErrorKind::kValue;
    err.file = name_;
    err.line = line_number_;
    err.column = static_cast<std::uint32_t>(kMaxLineLength + 1);
    err.message = fmt::format("line longer than {} characters", kMaxLineLength);
    return Read::kError;
}

bool LineSource::seek(const Position& p, Diagnostic& err) {
    if (failed_) return false;
    line_number_ = p.line_number;
    // Still buffered (a small loop body, or caller's text): no read at all.
    if (p.offset >= base_ && p.offset <= base_ + end_) {
        pos_ = static_cast<std::size_t>(p.offset - base_);
        return true;
    }
    if (file_ == nullptr || std::fseek(file_, static_cast<long>(p.offset), SEEK_SET) != 0) {
        failed_ = true;
        err.kind = ErrorKind::kIo;
        err.file = name_;
        err.line = p.line_number + 1;
        err.column = 1;
        err.message = fmt::format("cannot go back to offset {} to repeat a loop: {}", p.offset,
                                  file_ == nullptr ? "not in the text" : std::strerror(errno));
        return false;
    }
    base_ = p.offset;
    pos_ = end_ = 0;
    eof_ = false;
    return true;
}

}  // namespace apci::nc
