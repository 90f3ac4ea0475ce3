// SPDX-License-Identifier: MIT
#include "apci/nc/program.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "apci/nc/lexer.h"

namespace apci::nc {

EventStream::EventStream(LineSource source, InterpreterOptions options)
    : source_(std::move(source)),
      interpreter_(options),
      klartext_(KlartextOptions{options.start_position, options.tools}) {}

Result<EventStream> EventStream::open_file(const std::string& path, InterpreterOptions options) {
    Result<LineSource> source = LineSource::open_file(path);
    if (!source) return source.error();
    return EventStream(std::move(source).value(), options);
}

EventStream EventStream::from_text(std::string_view text, std::string name,
                                   InterpreterOptions options) {
    return EventStream(LineSource::from_text(text, std::move(name)), options);
}

bool EventStream::fail(Diagnostic d) {
    error_ = std::move(d);
    failed_ = true;
    return false;
}

bool EventStream::line(std::string_view text) {
    const std::uint64_t n = source_.line_number();
    if (dialect_ == Dialect::kUndecided) {
        dialect_ = detect_dialect(text).dialect;
    }
    if (dialect_ == Dialect::kKlartext) return klartext_line(text);
    if (!parse_din_line(text, n, source_.name(), parsed_, error_)) return fail(error_);
    switch (parsed_.kind) {
        case LineKind::kEmpty:
            return true;
        case LineKind::kProgramName:
            if (seen_block_ || !program_name_.empty()) {
                Diagnostic d;
                d.kind = ErrorKind::kSyntax;
                d.file = source_.name();
                d.line = n;
                d.column = parsed_.program_name_column - 1;
                d.message = "'%name' must be the first line of the program (and appear once)";
                return fail(std::move(d));
            }
            program_name_.assign(parsed_.program_name);
            return true;
        case LineKind::kBlock:
            seen_block_ = true;
            ++blocks_;
            if (!interpreter_.apply(parsed_.block, source_.name(), batch_, error_)) {
                return fail(error_);
            }
            return true;
    }
    return true;
}

bool EventStream::klartext_line(std::string_view text) {
    const std::uint64_t n = source_.line_number();
    if (!parse_klartext_line(text, n, source_.name(), klartext_block_, error_)) {
        return fail(error_);
    }
    if (klartext_block_.kind == KlartextKind::kEmpty) return true;
    ++blocks_;
    if (!klartext_.apply(klartext_block_, source_.name(), batch_, error_)) return fail(error_);
    if (klartext_block_.kind == KlartextKind::kBeginPgm) {
        program_name_ = klartext_.program_name();
    }
    return true;
}

bool EventStream::program_complete() const noexcept {
    return dialect_ == Dialect::kKlartext ? klartext_.state().closed : interpreter_.state().ended;
}

bool EventStream::read_batch() {
    batch_.clear();
    batch_pos_ = 0;
    std::string_view text;
    for (;;) {
        switch (source_.next(text, error_)) {
            case LineSource::Read::kError:
                return fail(error_);
            case LineSource::Read::kEnd:
                if (!program_complete()) {
                    Diagnostic d;
                    d.kind = ErrorKind::kProgramRule;
                    d.file = source_.name();
                    d.line = source_.line_number() == 0 ? 1 : source_.line_number();
                    d.column = 1;
                    d.message = dialect_ == Dialect::kKlartext ? "the program ends without END PGM"
                                                               : "the program ends without M30";
                    return fail(std::move(d));
                }
                at_end_ = true;
                return false;
            case LineSource::Read::kLine:
                if (!line(text)) return false;
                if (!batch_.empty()) return true;
                break;
        }
    }
}

EventStream::Next EventStream::next(Event& out) {
    if (failed_) return Next::kError;
    if (batch_pos_ >= batch_.size()) {
        if (at_end_) return Next::kEnd;
        if (!read_batch()) return failed_ ? Next::kError : Next::kEnd;
    }
    out = batch_[batch_pos_++];
    return Next::kEvent;
}

Result<ProgramSummary> validate(EventStream& stream) {
    ProgramSummary s;
    s.file = stream.file();
    Event ev;
    for (;;) {
        switch (stream.next(ev)) {
            case EventStream::Next::kEvent:
                ++s.events;
                if (std::holds_alternative<RapidMove>(ev.data) ||
                    std::holds_alternative<LineMove>(ev.data) ||
                    std::holds_alternative<ArcMove>(ev.data) ||
                    std::holds_alternative<VectorLineMove>(ev.data)) {
                    ++s.moves;
                }
                break;
            case EventStream::Next::kEnd:
                s.name = stream.program_name();
                s.lines = stream.lines_read();
                s.blocks = stream.blocks_read();
                return s;
            case EventStream::Next::kError:
                return stream.error();
        }
    }
}

namespace {

struct FileStamp {
    std::uint64_t size = 0;
    std::int64_t mtime_ns = 0;
};

bool stamp_file(const std::string& path, FileStamp& out, Diagnostic& err) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        err.kind = ErrorKind::kIo;
        err.file = path;
        err.line = 0;
        err.column = 0;
        err.message = fmt::format("cannot open: {}", std::strerror(errno));
        return false;
    }
    out.size = static_cast<std::uint64_t>(st.st_size);
    out.mtime_ns = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 +
                   static_cast<std::int64_t>(st.st_mtim.tv_nsec);
    return true;
}

}  // namespace

Result<Program> Program::load(const std::string& path, InterpreterOptions options) {
    Diagnostic err;
    FileStamp stamp;
    if (!stamp_file(path, stamp, err)) return err;
    Result<EventStream> stream = EventStream::open_file(path, options);
    if (!stream) return stream.error();
    Result<ProgramSummary> summary = validate(stream.value());
    if (!summary) return summary.error();
    Program p;
    p.summary_ = std::move(summary).value();
    p.options_ = options;
    p.from_file_ = true;
    p.file_size_ = stamp.size;
    p.file_mtime_ns_ = stamp.mtime_ns;
    return p;
}

Result<Program> Program::from_text(std::string_view text, std::string name,
                                   InterpreterOptions options) {
    EventStream stream = EventStream::from_text(text, std::move(name), options);
    Result<ProgramSummary> summary = validate(stream);
    if (!summary) return summary.error();
    Program p;
    p.summary_ = std::move(summary).value();
    p.options_ = options;
    p.text_ = text;
    return p;
}

Result<EventStream> Program::events() const {
    if (!from_file_) return EventStream::from_text(text_, summary_.file, options_);
    Diagnostic err;
    FileStamp now;
    if (!stamp_file(summary_.file, now, err)) return err;
    if (now.size != file_size_ || now.mtime_ns != file_mtime_ns_) {
        err.kind = ErrorKind::kIo;
        err.file = summary_.file;
        err.message = "the file changed since it was validated; load it again";
        return err;
    }
    return EventStream::open_file(summary_.file, options_);
}

}  // namespace apci::nc
