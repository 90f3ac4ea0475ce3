// SPDX-License-Identifier: MIT
// The one way a program is run (docs/data-path.md): `apcictl run`, `apcictl diff` and the Python
// module load what a run reads here, and build and drive the executor through ProgramRun. They
// keep only their own concerns: the command line and the outputs, the comparison of two boards,
// the Python objects. What differs between them is said in RunSettings, nowhere else.
//
//   inputs    the tool list, the correction table and the PLC script, loaded before the board
//             is touched (load_run_inputs); the first that cannot be read or does not parse is
//             the error;
//   program   validated whole before anything runs (open_validated), or, where nobody sees the
//             run's effects before it is over (the embedded emulator, every output held back),
//             validated while it runs (open_one_pass) and finished afterwards (finish);
//   sinks     the chain the executor feeds (one place): the self-approach check
//             (self_approach_sink.h) where the settings ask for it, and with threads the output
//             pipeline (pipeline.h) with the caller's sink behind it: the check before the
//             pipeline where a finding stops the run (it must stop there), after it (on the
//             writer thread) where it only warns;
//   refusals  a program that does not validate because it needs an input that was not given
//             (D n without a tool list, FUNCTION CORRDATA without a correction table) says so
//             in the caller's words for that input, decided by the diagnostic's kind
//             (nc::Undefined), never by its text.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "apci/apci.hpp"
#include "apci/nc/correction_table.h"
#include "apci/nc/diagnostic.h"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/board_words.h"
#include "apci/run/cpu_placement.h"
#include "apci/run/executor.h"
#include "apci/run/pipeline.h"
#include "apci/run/plc_script.h"
#include "apci/run/self_approach_sink.h"

namespace apci::run {

// Where a run's inputs besides the program come from; nullopt: not given.
struct RunInputFiles {
    std::optional<std::string> tools;  // a tool list file (nc/tools.h), or its text
    bool tools_is_text = false;
    std::optional<std::string> corrections;  // a correction table file (nc/correction_table.h)
    std::optional<std::string> plc;          // a PLC script file (plc_script.h)
    // The caller's words for the tool list and the correction table, in the refusal of a
    // program that needs one not given: "(no --tools file given)".
    std::string tools_name = "tool list";
    std::string corrections_name = "correction table";
};

// What a run reads besides the program.
struct RunInputs {
    nc::ToolTable tools;              // empty when not given: every D n (n > 0) is refused
    nc::CorrectionTable corrections;  // empty when not given: every CORRDATA row is refused
    std::optional<PlcScript> plc;
    bool tools_given = false;
    bool corrections_given = false;
    std::string tools_name = "tool list";
    std::string corrections_name = "correction table";
};

// Loads the inputs `files` names, in the order tool list, correction table, PLC script.
nc::Result<RunInputs> load_run_inputs(const RunInputFiles& files);

// A refusal of the program, with the input it needed named where that input was not given.
nc::Diagnostic name_missing_input(nc::Diagnostic d, const RunInputs& inputs);

// The self-approach check's modes by the names the command line and Python give them ("warn",
// "error", "off"); nullopt for another name.
std::optional<SelfApproachMode> self_approach_mode(std::string_view name) noexcept;

// The embedded emulator ("emu:", "emu:?no-option-tc", or no device given): a board inside this
// process, which nothing else sees and which ends with it (apci.h, apci_open).
bool embedded_emulator(std::string_view uri) noexcept;

// What a caller chooses about a run.
struct RunSettings {
    SelfApproachMode self_approach = SelfApproachMode::kWarn;
    // 0: no bottleneck avoidance, else ProgramExecutor::kMinBottleneckBlocks..kMax...
    int bottleneck_blocks = 0;
    // The NC front end on a thread of its own (read_ahead.h) and the caller's sink on another
    // (pipeline.h); off, everything runs on the caller's thread (the same calls in the same
    // order: for debugging). With `cpus` (which must outlive the run), the helper threads are
    // placed as that says.
    bool threads = false;
    const CpuPlacement* cpus = nullptr;
    // The board moves a machine (a daemon's, a real one: not the embedded emulator, whose run
    // is its own dry run): with the self-approach check an error, open_validated() runs the
    // program first on an embedded emulator set up as the board stands, and refuses it at a
    // finding there, before anything moves (its findings come only after the moves otherwise).
    bool dry_run_first = false;
    // What the run's errors say, after a lost link's cause, the user does to open the link
    // again (board_words.h): apcictl's next command does; a Python program calls apci.open().
    std::string lost_link_hint = std::string(kLostLinkHint);
};

// A program: a file, or a text the caller holds (it must outlive the run).
struct ProgramSource {
    std::string path;  // the file, when `text` is empty
    std::optional<std::string_view> text;
    std::string name;  // the name in messages and outputs: the path, "<stdin>", "<program>"

    static ProgramSource file(std::string path) {
        ProgramSource s;
        s.name = path;
        s.path = std::move(path);
        return s;
    }
    static ProgramSource in_memory(std::string_view text, std::string name) {
        ProgramSource s;
        s.text = text;
        s.name = std::move(name);
        return s;
    }
};

// One run of one program on a board: the one place the program executor is built. `board`,
// `sink` and `inputs` must outlive it. Use: open_validated() or open_one_pass(), then run(),
// then finish().
class ProgramRun {
  public:
    ProgramRun(apci::Board& board, RunSink& sink, const RunInputs& inputs,
               const RunSettings& settings);
    // The check's pipeline ends first (its thread calls the check), then the check, then the
    // writers' pipeline behind it.
    ~ProgramRun();
    ProgramRun(const ProgramRun&) = delete;
    ProgramRun& operator=(const ProgramRun&) = delete;

    // The NC front end's options for this board (ProgramExecutor::interpreter_options): where
    // the axes stand, the board's cycle, the inputs to check D n and CORRDATA against.
    const nc::InterpreterOptions& options() const noexcept { return options_; }

    // Validates the whole program before anything runs; the refusal, or nothing. With
    // RunSettings::dry_run_first and the check an error, a self-approach finding of the dry run
    // is a refusal too.
    std::optional<nc::Diagnostic> open_validated(const ProgramSource& source);
    // Opens the program to be validated while it runs (nc::SinglePass): the caller holds its
    // outputs back until finish() says the program was valid. A file that cannot be opened is
    // refused here.
    std::optional<nc::Diagnostic> open_one_pass(const ProgramSource& source);
    // Turns an open one-pass program into one validated before it runs (nothing has run yet):
    // the refusal, or nothing. Nothing to do for a program opened validated.
    std::optional<nc::Diagnostic> validate_first();

    bool one_pass() const noexcept { return single_.has_value(); }
    // In one pass: the program's size in bytes (0 for a pipe). Validated: 0.
    std::uint64_t program_bytes() const noexcept;
    // Validated: the program's blocks. In one pass: 0 (known after finish()).
    std::uint64_t validated_blocks() const noexcept;

    // Executes the program opened, to its end or to the first error; with threads, every call
    // has reached the caller's sink when it returns (the writer thread has ended, and an
    // exception the caller's sink threw there is thrown here). The outcome holds the
    // self-approach check's findings.
    RunOutcome run();
    // After run(): in one pass, the rest of the program validated (its refusal, or nothing);
    // the outcome's totals get the program's name and block count.
    std::optional<nc::Diagnostic> finish(RunOutcome& outcome);

  private:
    nc::EventStream& events();
    // The chain of sinks in front of `sink` the settings ask for; its head.
    RunSink& chain(RunSink& sink, const RunSettings& settings);

    // Where the reader and the writers' thread run: on either CPU where the check has a
    // thread of its own, else on the helpers' (cpu_placement.h).
    static HelperCpu helpers_beside_check(const RunSettings& settings) noexcept;

    // The chain's links, declared before the executor that feeds them (and in the order that
    // packs them: the destructor ends them in the order they feed each other).
    std::optional<PipelinedSink> output_;
    std::optional<PipelinedSink> pipeline_;
    std::optional<SelfApproachSink> check_;
    apci::Board& board_;
    const RunInputs& inputs_;
    RunSink& head_;
    nc::InterpreterOptions options_;
    ProgramExecutor executor_;
    ProgramSource source_;
    std::optional<nc::Program> program_;
    std::optional<nc::EventStream> stream_;
    std::optional<nc::SinglePass> single_;
    // What the dry run takes of the settings (RunSettings::dry_run_first): whether there is
    // one, and how the program runs (the bottleneck avoidance changes the path).
    int bottleneck_blocks_ = 0;
    bool threads_ = false;
    bool dry_run_ = false;
};

// A run validated first, as `apcictl diff` and the Python module run: the refusal of a program
// that does not validate, or what the run did (its totals with the program's name and blocks).
nc::Result<RunOutcome> run_program(apci::Board& board, RunSink& sink, const RunInputs& inputs,
                                   const ProgramSource& source, const RunSettings& settings);

}  // namespace apci::run
