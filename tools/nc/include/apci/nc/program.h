// SPDX-License-Identifier: MIT
// Streaming NC programs: text -> lines -> blocks -> events with flat memory (one line buffer,
// one block, one batch of at most EventBatch::kCapacity events; nothing kept per block).
//
// Two passes make "nothing is executed from a program that does not parse" hold for streamed
// input (docs/design.md section 8): Program::load() reads the whole program once, parsing and
// interpreting every block but keeping no event (the validation pass); only a program that
// passed gives an EventStream for the execution pass, which reads it again.
//
// Where what runs is seen by no one until the whole program proved valid (apcictl run on the
// embedded emulator, whose outputs are published only at the end), SinglePass folds the two
// into one: the execution reads the stream and SinglePass::finish() reads the rest, giving
// the answer Program::load would have given.
#pragma once

#include <array>
#include <bitset>
#include <cstdint>
#include <optional>
#include <vector>
#include <string>
#include <string_view>

#include "apci/nc/diagnostic.h"
#include "apci/nc/events.h"
#include "apci/nc/interpreter.h"
#include "apci/nc/klartext.h"
#include "apci/nc/parser.h"
#include "apci/nc/source.h"

namespace apci::nc {

// Where the V.G. variables come from while a program executes: the board's values (the
// executor's). Without one the stream uses the interpreter's own view (model_variable).
class VariableSource {
  public:
    virtual ~VariableSource() = default;
    // False with `why` when the value cannot be read.
    virtual bool read(const VariableRef& v, double& out, std::string& why) = 0;
    // True (asked after read()) when the source has no board behind it any more: the run it
    // served stopped while the stream read ahead of it (apci::run::ReadAhead). The stream then
    // reads this variable, and those after it, with its own view, as if the source had been
    // taken away (set_variable_source(nullptr)) before: read() answered nothing, and
    // read_variable_source() stays as it was.
    virtual bool withdrawn() const noexcept { return false; }
};

// $FOR loops nest at most this deep (the replay keeps one position per level: flat memory).
inline constexpr std::size_t kMaxLoopDepth = 16;

// One pass over a program, pulling one event at a time.
class EventStream : private ExpressionContext {
  public:
    static Result<EventStream> open_file(const std::string& path,
                                         const InterpreterOptions& options = {});
    // The text must outlive the stream; nothing is copied.
    static EventStream from_text(std::string_view text, std::string name,
                                 const InterpreterOptions& options = {});

    enum class Next { kEvent, kEnd, kError };
    // kEvent: `out` holds the next event. kEnd: the program ended with M30 and only blank or
    // comment lines follow. kError: error() says why; every later call returns kError again.
    Next next(Event& out);

    const Diagnostic& error() const noexcept { return error_; }
    // The dialect, known once the first significant line was read.
    Dialect dialect() const noexcept { return dialect_; }
    // The modal state of a DIN 66025 program ...
    const ModalState& state() const noexcept { return interpreter_.state(); }
    // ... and of a Klartext program.
    const KlartextState& klartext_state() const noexcept { return klartext_.state(); }
    const std::string& file() const noexcept { return source_.name(); }
    // The "%name" (DIN 66025) or BEGIN PGM name (Klartext) of the program, empty when none.
    const std::string& program_name() const noexcept { return program_name_; }
    std::uint64_t lines_read() const noexcept { return source_.line_number(); }
    std::uint64_t blocks_read() const noexcept { return blocks_; }
    // Events, and move events among them (rapid, line, arc, vector line), handed out so far.
    std::uint64_t events_read() const noexcept { return events_; }
    std::uint64_t moves_read() const noexcept { return moves_; }
    // Bytes of the program read so far (where the next line starts; $FOR loops go back).
    std::uint64_t offset() const noexcept { return source_.tell().offset; }
    // True once a variable was read from the VariableSource (not the interpreter's view): the
    // events from then on may differ from those of a validation pass.
    bool read_variable_source() const noexcept { return read_variable_source_; }
    // The board's variables for the rest of the pass (not owned; null: the interpreter's view).
    void set_variable_source(VariableSource* source) noexcept { variables_ = source; }
    // P parameter n, if set.
    std::optional<double> parameter_value(int n) const noexcept;

  private:
    struct LoopFrame {
        ForLoop loop;
        LineSource::Position body;  // where the line after $FOR starts
        std::uint64_t line = 0;     // of the $FOR
        std::uint32_t column = 0;
        std::int64_t block = kNoBlockNumber;  // the $FOR line's N number
        std::uint64_t repetitions = 0;        // bodies run again since this $FOR
    };
    // ExpressionContext
    bool parameter(int n, double& out) const override;
    bool variable(const VariableRef& v, double& out, std::string& why) const override;
    bool loop_start(const IsgLine& isg);
    bool loop_end(const IsgLine& isg);
    bool skip_loop(const IsgLine& isg);
    bool loop_continues(const LoopFrame& f) const noexcept;
    // Counts a block run inside a $FOR loop (asked only while one is open); false (error)
    // beyond max_loop_blocks.
    bool count_loop_block();
    Diagnostic here(ErrorKind kind, std::uint32_t column, std::string message) const;

    EventStream(LineSource source, const InterpreterOptions& options);
    bool read_batch();  // fills batch_ from the next block with events; false at end or error
    bool fail(Diagnostic d);
    bool line(std::string_view text);
    bool klartext_line(std::string_view text);
    bool program_complete() const noexcept;  // M30 (DIN 66025) or END PGM (Klartext) seen

    LineSource source_;
    Interpreter interpreter_;
    ParsedLine parsed_;
    KlartextInterpreter klartext_;
    KlartextBlock klartext_block_;
    EventBatch batch_;
    std::size_t batch_pos_ = 0;
    Dialect dialect_ = Dialect::kUndecided;
    bool seen_block_ = false;
    bool tape_start_ = false, tape_end_ = false;  // a '%' alone seen first, after the end
    bool at_end_ = false;
    bool failed_ = false;
    std::uint64_t blocks_ = 0;
    std::uint64_t events_ = 0;
    std::uint64_t moves_ = 0;
    mutable bool read_variable_source_ = false;  // set in variable(), a const override
    std::string program_name_;
    Diagnostic error_;
    VariableSource* variables_ = nullptr;
    std::array<double, kParameterCount> params_{};
    std::bitset<kParameterCount> params_set_;
    std::vector<LoopFrame> loops_;  // at most kMaxLoopDepth
    std::uint64_t loop_blocks_ = 0;  // blocks run inside $FOR loops, repetitions counted
    std::uint64_t max_loop_blocks_ = kMaxLoopBlocks;
};

struct ProgramSummary {
    std::string file;
    std::string name;          // "%name" or BEGIN PGM name, empty when the program has none
    std::uint64_t lines = 0;   // source lines
    std::uint64_t blocks = 0;  // lines holding a block
    std::uint64_t events = 0;
    std::uint64_t moves = 0;  // rapid, line, arc and vector line events
};

// Runs the whole stream, keeping nothing but counts: the validation pass.
Result<ProgramSummary> validate(EventStream& stream);
// Reads what is left of the stream, keeping nothing: the summary of the whole stream (counts
// from its start) or its first error. validate() is this on a fresh stream.
Result<ProgramSummary> drain(EventStream& stream);

// A program that passed validation and can be executed (streamed again) any number of times.
class Program {
  public:
    // Validates the file; the error is the first one in the program.
    static Result<Program> load(const std::string& path, const InterpreterOptions& options = {});
    // Validates text held by the caller (it must outlive the Program and its streams).
    static Result<Program> from_text(std::string_view text, std::string name,
                                     const InterpreterOptions& options = {});

    const ProgramSummary& summary() const noexcept { return summary_; }
    // The execution pass. For a file, fails with kIo when the file changed (size or time of
    // last change) since validation; the stream re-checks every block anyway.
    Result<EventStream> events() const;

  private:
    Program() = default;
    ProgramSummary summary_;
    InterpreterOptions options_;
    bool from_file_ = false;
    std::string_view text_;
    std::uint64_t file_size_ = 0;
    std::int64_t file_mtime_ns_ = 0;
};

// One pass that is both the execution and the validation, for a run whose effects nobody sees
// before the whole program proved valid (the caller keeps its outputs back until finish()
// said so). The caller executes events() (to its end, or until it stops), then finish() reads
// the rest of the program and gives what Program::load would have: the program's first error
// or its summary. A stream that read variables from a VariableSource may have taken another
// way than the validation pass (which sees the interpreter's own values), so finish() then
// validates the program once more on its own, as Program::load does.
class SinglePass {
  public:
    static Result<SinglePass> open_file(const std::string& path,
                                        const InterpreterOptions& options = {});
    // The text must outlive the pass; nothing is copied.
    static SinglePass from_text(std::string_view text, std::string name,
                                const InterpreterOptions& options = {});

    EventStream& events() noexcept { return stream_; }
    const EventStream& events() const noexcept { return stream_; }
    // The program's size in bytes (of the file when it was opened; 0 for a pipe): with
    // events().offset(), how far the pass has come.
    std::uint64_t size() const noexcept { return size_; }
    // Reads the rest of the stream (without a VariableSource) and answers as Program::load.
    Result<ProgramSummary> finish();

  private:
    SinglePass(EventStream stream, const InterpreterOptions& options)
        : stream_(std::move(stream)), options_(options) {}
    Result<ProgramSummary> validate_again() const;

    EventStream stream_;
    InterpreterOptions options_;
    bool from_file_ = false;
    bool regular_file_ = false;
    std::string_view text_;
    std::uint64_t size_ = 0;
    std::int64_t file_mtime_ns_ = 0;
};

}  // namespace apci::nc
