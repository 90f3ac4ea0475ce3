// SPDX-License-Identifier: MIT
#include "apci/nc/program.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <string_view>
#include <utility>
#include <variant>

#include "apci/nc/lexer.h"

namespace apci::nc {

EventStream::EventStream(LineSource source, const InterpreterOptions& options)
    : source_(std::move(source)),
      interpreter_(options),
      klartext_(KlartextOptions{options.start_position, options.tools, options.corrections,
                                options.cycle_seconds}),
      max_loop_blocks_(options.max_loop_blocks) {
    loops_.reserve(kMaxLoopDepth);
}

Result<EventStream> EventStream::open_file(const std::string& path,
                                               const InterpreterOptions& options) {
    Result<LineSource> source = LineSource::open_file(path);
    if (!source) return source.error();
    return EventStream(std::move(source).value(), options);
}

EventStream EventStream::from_text(std::string_view text, std::string name,
                                   const InterpreterOptions& options) {
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
    if (!parse_din_line(text, n, source_.name(), parsed_, error_, this)) return fail(error_);
    const bool is_block = parsed_.kind == LineKind::kIsg || parsed_.kind == LineKind::kAssignment ||
                          parsed_.kind == LineKind::kBlock;
    if (is_block && !loops_.empty() && !count_loop_block()) return false;
    switch (parsed_.kind) {
        case LineKind::kIsg:
            seen_block_ = true;
            ++blocks_;
            if (parsed_.isg.kind == IsgKind::kFor) return loop_start(parsed_.isg);
            if (parsed_.isg.kind == IsgKind::kEndFor) return loop_end(parsed_.isg);
            if (!interpreter_.apply_isg(parsed_.isg, parsed_.block, source_.name(), batch_, error_))
                return fail(error_);
            return true;
        case LineKind::kAssignment:
            seen_block_ = true;
            ++blocks_;
            if (interpreter_.state().ended)
                return fail(here(ErrorKind::kProgramRule, 1, std::string(kBlockAfterEnd)));
            if (parsed_.assignment.to_parameter) {
                const auto i = static_cast<std::size_t>(parsed_.assignment.parameter);
                params_[i] = parsed_.assignment.value;
                params_set_.set(i);
                return true;
            }
            if (!interpreter_.apply_variable_write(parsed_.assignment, parsed_.block,
                                                   source_.name(), batch_, error_))
                return fail(error_);
            return true;
        case LineKind::kEmpty:
            return true;
        case LineKind::kTapeMark: {
            // The tape's start mark before everything else, its end mark after the program's
            // end; then nothing but blank lines and comments (docs/nc-programs.md).
            const bool at_start = !seen_block_ && !tape_start_ && program_name_.empty();
            const bool at_end = interpreter_.state().ended && !tape_end_;
            if (!at_start && !at_end) {
                Diagnostic d;
                d.kind = ErrorKind::kProgramRule;
                d.file = source_.name();
                d.line = n;
                d.column = parsed_.program_name_column - 1;
                d.message = "'%' alone marks the tape's start (the first line) or its end (after "
                            "M30 or M2), once each";
                return fail(std::move(d));
            }
            (at_start ? tape_start_ : tape_end_) = true;
            return true;
        }
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
                if (!loops_.empty()) {
                    const LoopFrame& f = loops_.back();
                    Diagnostic d;
                    d.kind = ErrorKind::kProgramRule;
                    d.file = source_.name();
                    d.line = f.line;
                    d.column = f.column;
                    d.message = "$FOR without $ENDFOR: the program ends inside the loop";
                    return fail(std::move(d));
                }
                if (!program_complete()) {
                    Diagnostic d;
                    d.kind = ErrorKind::kProgramRule;
                    d.file = source_.name();
                    d.line = source_.line_number() == 0 ? 1 : source_.line_number();
                    d.column = 1;
                    const std::string_view end =
                        dialect_ == Dialect::kKlartext ? "END PGM" : "M30";
                    d.message = blocks_ == 0
                                    ? fmt::format("the program has no blocks: nothing to run (a "
                                                  "program's blocks end with {})",
                                                  end)
                                    : fmt::format("the program ends without {}", end);
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
    ++events_;
    if (std::holds_alternative<RapidMove>(out.data) || std::holds_alternative<LineMove>(out.data) ||
        std::holds_alternative<ArcMove>(out.data) ||
        std::holds_alternative<VectorLineMove>(out.data))
        ++moves_;
    return Next::kEvent;
}

// ---- Expressions and loops

std::optional<double> EventStream::parameter_value(int n) const noexcept {
    if (n < 0 || n >= kParameterCount || !params_set_.test(static_cast<std::size_t>(n)))
        return std::nullopt;
    return params_[static_cast<std::size_t>(n)];
}

bool EventStream::parameter(int n, double& out) const {
    const std::optional<double> v = parameter_value(n);
    if (!v) return false;
    out = *v;
    return true;
}

namespace {

// [ISG-OTC] section 2.8: the wear values are "in [mm] oder [Inch]": a length in the program's
// input unit (G70 inch, G71 mm). The wear on A, B, C (axes 3..5, rotary by DIN 66025's names)
// is an angle; the wear constant is 0.1 um/m and OTC_ACTIVE a flag in either unit.
bool is_wear_length(const VariableRef& v) noexcept {
    switch (v.variable) {
        case NcVariable::kWearRadius:
        case NcVariable::kWearRadiusCont:
            return true;
        case NcVariable::kWear:
            return v.index < 3 || v.index > 5;
        default:
            return false;
    }
}

}  // namespace

bool EventStream::variable(const VariableRef& v, double& out, std::string& why) const {
    bool ok = true;
    if (variables_ != nullptr) {
        ok = variables_->read(v, out, why);
        if (!variables_->withdrawn()) {
            read_variable_source_ = true;
        } else {
            why.clear();
            ok = true;
            out = interpreter_.model_variable(v);
        }
    } else {
        out = interpreter_.model_variable(v);
    }
    if (ok && is_wear_length(v) && interpreter_.state().units == Units::kInch)
        out /= kMillimetresPerInch;
    return ok;
}

Diagnostic EventStream::here(ErrorKind kind, std::uint32_t column, std::string message) const {
    Diagnostic d;
    d.kind = kind;
    d.file = source_.name();
    d.line = source_.line_number();
    d.column = column == 0 ? 1 : column;
    d.block = parsed_.block.block_number();
    d.klartext = dialect_ == Dialect::kKlartext;
    d.message = std::move(message);
    return d;
}

bool EventStream::loop_continues(const LoopFrame& f) const noexcept {
    const double p = params_[static_cast<std::size_t>(f.loop.parameter)];
    return f.loop.step > 0.0 ? p <= f.loop.end : p >= f.loop.end;
}

bool EventStream::loop_start(const IsgLine& isg) {
    if (interpreter_.state().ended)
        return fail(here(ErrorKind::kProgramRule, 1, std::string(kBlockAfterEnd)));
    if (loops_.size() >= kMaxLoopDepth)
        return fail(here(ErrorKind::kProgramRule, isg.column,
                         fmt::format("$FOR nested deeper than {} loops", kMaxLoopDepth)));
    const auto i = static_cast<std::size_t>(isg.loop.parameter);
    params_[i] = isg.loop.start;
    params_set_.set(i);
    LoopFrame f{isg.loop, source_.tell(), source_.line_number(), isg.column,
                parsed_.block.block_number()};
    if (!loop_continues(f)) return skip_loop(isg);
    loops_.push_back(f);
    return true;
}

// The condition fails at once: the body is skipped to its $ENDFOR, unparsed.
bool EventStream::skip_loop(const IsgLine& isg) {
    const std::uint64_t for_line = source_.line_number();
    std::size_t depth = 1;
    std::string_view text;
    for (;;) {
        switch (source_.next(text, error_)) {
            case LineSource::Read::kError:
                return fail(error_);
            case LineSource::Read::kEnd: {
                Diagnostic d;
                d.kind = ErrorKind::kProgramRule;
                d.file = source_.name();
                d.line = for_line;
                d.column = isg.column;
                d.message = "$FOR without $ENDFOR: the program ends inside the loop";
                return fail(std::move(d));
            }
            case LineSource::Read::kLine:
                switch (loop_marker(text)) {
                    case LoopMarker::kFor: ++depth; break;
                    case LoopMarker::kEndFor:
                        if (--depth == 0) return true;
                        break;
                    case LoopMarker::kNone: break;
                }
                break;
        }
    }
}

bool EventStream::loop_end(const IsgLine& isg) {
    if (loops_.empty())
        return fail(here(ErrorKind::kProgramRule, isg.column, "$ENDFOR without $FOR"));
    LoopFrame& f = loops_.back();
    const auto i = static_cast<std::size_t>(f.loop.parameter);
    params_[i] += f.loop.step;
    if (!std::isfinite(params_[i]))
        return fail(here(ErrorKind::kValue, isg.column, "the $FOR parameter is no longer finite"));
    if (!loop_continues(f)) {
        loops_.pop_back();
        return true;
    }
    if (!source_.seek(f.body, error_)) return fail(error_);
    ++f.repetitions;
    return true;
}

// The loop named is the open one that repeated most since its $FOR: the one that does not end
// (an inner loop that ends and starts again inside an endless outer one repeats less).
bool EventStream::count_loop_block() {
    if (++loop_blocks_ <= max_loop_blocks_) return true;
    const LoopFrame* worst = &loops_.back();
    for (const LoopFrame& f : loops_)
        if (f.repetitions > worst->repetitions) worst = &f;
    Diagnostic d;
    d.kind = ErrorKind::kProgramRule;
    d.file = source_.name();
    d.line = worst->line;
    d.column = worst->column;
    d.block = worst->block;
    d.message = fmt::format(
        "$FOR P{} does not end: $FOR loops may run at most {} blocks in all, every repetition "
        "counted, and this loop has repeated its body {} times: does the body set P{} back, or "
        "is the end value too far?",
        worst->loop.parameter, max_loop_blocks_, worst->repetitions, worst->loop.parameter);
    return fail(std::move(d));
}

Result<ProgramSummary> drain(EventStream& stream) {
    Event ev;
    for (;;) {
        switch (stream.next(ev)) {
            case EventStream::Next::kEvent:
                break;
            case EventStream::Next::kEnd: {
                ProgramSummary s;
                s.file = stream.file();
                s.name = stream.program_name();
                s.lines = stream.lines_read();
                s.blocks = stream.blocks_read();
                s.events = stream.events_read();
                s.moves = stream.moves_read();
                return s;
            }
            case EventStream::Next::kError:
                return stream.error();
        }
    }
}

Result<ProgramSummary> validate(EventStream& stream) {
    return drain(stream);
}

namespace {

struct FileStamp {
    std::uint64_t size = 0;
    std::int64_t mtime_ns = 0;
    bool regular = false;  // a regular file (not a pipe or a device): it can be read again
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
    out.regular = S_ISREG(st.st_mode);
    return true;
}

}  // namespace

Result<Program> Program::load(const std::string& path, const InterpreterOptions& options) {
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
                                   const InterpreterOptions& options) {
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

// ---- One pass: execution and validation together

Result<SinglePass> SinglePass::open_file(const std::string& path,
                                         const InterpreterOptions& options) {
    // The same checks, in the same order, as Program::load: the same error for a file that
    // cannot be had.
    Diagnostic err;
    FileStamp stamp;
    if (!stamp_file(path, stamp, err)) return err;
    Result<EventStream> stream = EventStream::open_file(path, options);
    if (!stream) return stream.error();
    SinglePass p(std::move(stream).value(), options);
    p.from_file_ = true;
    p.regular_file_ = stamp.regular;
    p.size_ = stamp.regular ? stamp.size : 0;
    p.file_mtime_ns_ = stamp.mtime_ns;
    return p;
}

SinglePass SinglePass::from_text(std::string_view text, std::string name,
                                 const InterpreterOptions& options) {
    SinglePass p(EventStream::from_text(text, std::move(name), options), options);
    p.text_ = text;
    p.size_ = text.size();
    return p;
}

Result<ProgramSummary> SinglePass::finish() {
    // The caller's source (the executor's board) may be gone; the rest is read as the
    // validation pass reads it.
    stream_.set_variable_source(nullptr);
    Result<ProgramSummary> summary = drain(stream_);
    if (!stream_.read_variable_source()) return summary;
    return validate_again();
}

Result<ProgramSummary> SinglePass::validate_again() const {
    if (!from_file_) {
        Result<Program> p = Program::from_text(text_, stream_.file(), options_);
        if (!p) return p.error();
        return p.value().summary();
    }
    Diagnostic err;
    err.kind = ErrorKind::kIo;
    err.file = stream_.file();
    if (!regular_file_) {
        err.message =
            "the program reads variables of the board and is not a regular file (a pipe?), so "
            "it cannot be read a second time to validate it; save it to a file and run that";
        return err;
    }
    FileStamp now;
    if (!stamp_file(stream_.file(), now, err)) return err;
    if (now.size != size_ || now.mtime_ns != file_mtime_ns_) {
        err.message = "the file changed while it ran; run it again";
        return err;
    }
    Result<Program> p = Program::load(stream_.file(), options_);
    if (!p) return p.error();
    return p.value().summary();
}

}  // namespace apci::nc
