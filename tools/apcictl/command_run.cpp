// SPDX-License-Identifier: MIT
// `run PROGRAM.nc [--tools F] [--svg F] [--json F] [--csv F]`: executes an NC program on the
// board (docs/design.md section 7): validation pass first (nothing runs from a program that does
// not parse), then the events drive the board through libapci (apci_run's ProgramRun,
// program_run.h), the executed path streams into the outputs, and a summary goes to standard
// output. On the embedded emulator, whose board nobody else sees, the two passes are one
// (nc::SinglePass): the outputs are published only once the whole program proved valid.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "apci/nc/correction_table.h"
#include "apci/nc/program.h"
#include "apci/nc/tools.h"
#include "apci/run/csv_writer.h"
#include "apci/run/executor.h"
#include "apci/run/json_writer.h"
#include "apci/run/plc_script.h"
#include "apci/run/program_run.h"
#include "apci/run/run_files.h"
#include "apci/run/summary.h"
#include "apci/run/svg_writer.h"
#include "arguments.h"
#include "command.h"
#include "run_inputs.h"
#include "run_report.h"

namespace apcictl {
namespace {

using apci::run::OutputFile;
using apci::run::PathSegment;
using apci::run::RunError;

// A program held in memory, at most apci::run::kStdinProgramLimit: one read from standard input
// (`fd` 0, "-"), or from a file that is not regular (a pipe: /dev/stdin, a shell's <(...), a
// FIFO, a device), which cannot be read twice as a file is (on a board other than the embedded
// emulator it is read twice: validation, then execution; a second read of a pipe found it
// empty: "the program ends without M30"). Empty on success, else why not.
std::string read_whole_program(int fd, const std::string& name, std::string& text) {
    int error = 0;
    switch (apci::run::read_bounded(fd, apci::run::kStdinProgramLimit, text, error)) {
        case apci::run::BoundedRead::kOk:
            return {};
        case apci::run::BoundedRead::kTooLarge:
            text.clear();
            return name == "-" ? fmt::format(
                                     "standard input is larger than {} MiB; save the "
                                     "program to a file and give its path instead of -",
                                     apci::run::kStdinProgramLimit >> 20)
                               : fmt::format(
                                     "{} is not a regular file and is larger than {} "
                                     "MiB; save the program to a file and give its path",
                                     name, apci::run::kStdinProgramLimit >> 20);
        case apci::run::BoundedRead::kError:
            break;
    }
    return fmt::format("cannot read {}: {}", name == "-" ? "standard input" : name,
                       std::strerror(error));
}

// Whether `path` can be read twice (a regular file); false for a pipe, a FIFO, a device, and
// for a path that cannot be examined (its open fails later, with its reason).
bool seekable(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode);
}

// Whether `target` is where standard output goes (the same open file: /dev/stdout, a
// /proc/self/fd link to it), so that the summary is not mixed into that output.
bool names_standard_output(const std::string& target) {
    struct stat out {};
    struct stat st {};
    return !target.empty() && target != "-" && ::fstat(STDOUT_FILENO, &out) == 0 &&
           ::stat(target.c_str(), &st) == 0 && st.st_dev == out.st_dev && st.st_ino == out.st_ino;
}

// The first error that says the run could not go on for want of its board or its host (the
// link failed or timed out, a reply was garbled, memory ran out), not that the board refused a
// move; null when there is none.
const RunError* link_failure(const std::vector<RunError>& errors) {
    constexpr std::array kLost{APCI_TRANSPORT_ERROR, APCI_TIMEOUT, APCI_BAD_FRAME,
                               APCI_UNKNOWN_OPCODE, APCI_NO_MEMORY};
    for (const RunError& e : errors)
        for (const apci_status s : kLost)
            if (e.code == apci::status_name(s)) return &e;
    return nullptr;
}

// An output (or none) that is held back in a temporary file until the run is published
// (run_files.h): not standard output, nor an existing file that is written where it stands (a
// FIFO, a device). A target that cannot be opened fails at its open.
bool held_back(const std::string& target) {
    if (target.empty()) return true;
    if (target == "-") return false;
    struct stat st {};
    return ::stat(target.c_str(), &st) != 0 || S_ISREG(st.st_mode) || S_ISDIR(st.st_mode);
}

// Where the run's output goes: the writers the user asked for, the plot, a progress bar.
class Outputs final : public apci::run::RunSink {
  public:
    std::unique_ptr<apci::run::JsonRunWriter> json;
    std::unique_ptr<apci::run::SvgPlotWriter> svg;
    std::FILE* csv_file = nullptr;
    std::unique_ptr<apci::run::TraceCsvWriter> csv;
    std::uint64_t total_blocks = 0;
    // One pass: the total is known only at its end; how far the pass has come is the byte
    // position in the program (of program_bytes; 0 when unknown, a pipe).
    bool one_pass = false;
    std::uint64_t program_bytes = 0;
    bool progress_bar = false;

    void programmed(const PathSegment& s) override {
        if (svg) svg->programmed(s);
    }
    bool wants_programmed() const override { return svg != nullptr; }
    bool takes_programmed() const override { return svg != nullptr; }
    void executed(const PathSegment& s) override {
        if (json) json->segment(s);
        if (svg) svg->executed(s);
    }
    bool svg_cycles = false;  // --svg-cycles: the per-cycle axes in the plot
    bool wants_samples() const override { return csv_file != nullptr || (svg && svg_cycles); }
    void axes(std::span<const std::string> names) override {
        if (csv_file != nullptr) csv = std::make_unique<apci::run::TraceCsvWriter>(csv_file, names);
    }
    void axis_numbers(const std::array<int, 3>& xyz) override { xyz_ = xyz; }
    void sample(std::uint64_t cycle, double time_s, std::span<const double> axes) override {
        if (csv) csv->sample(cycle, time_s, axes);
        if (svg && svg_cycles)
            svg->cycle(apci::run::Point(axes[static_cast<std::size_t>(xyz_[0])],
                                        axes[static_cast<std::size_t>(xyz_[1])],
                                        axes[static_cast<std::size_t>(xyz_[2])]));
    }
    void error(const RunError& e, const apci::run::Point& where) override {
        if (svg) svg->error_marker(e.block, where, e.code);
    }
    void warning(const RunError& w, const apci::run::Point& where) override {
        if (svg) svg->warning_marker(w.block, where, w.code);
    }
    void progress(std::uint64_t blocks, std::uint64_t offset) override {
        const bool by_bytes = total_blocks == 0 && one_pass && program_bytes != 0;
        if (!progress_bar || (total_blocks == 0 && !by_bytes)) return;
        const auto now = std::chrono::steady_clock::now();
        if (now - last_draw_ < std::chrono::milliseconds(100)) return;
        last_draw_ = now;
        if (by_bytes) {
            draw(static_cast<double>(offset) / static_cast<double>(program_bytes),
                 fmt::format("{} blocks", blocks));
        } else {
            draw(static_cast<double>(blocks) / static_cast<double>(total_blocks),
                 fmt::format("{} of {} blocks", blocks, total_blocks));
        }
    }
    // The one pass ended with the program valid: a bar on the screen shows the total.
    void completed(std::uint64_t blocks) {
        if (drawn_) draw(1.0, fmt::format("{} of {} blocks", blocks, blocks));
    }
    void clear_progress() {
        if (drawn_) fmt::print(stderr, "\r\x1b[K");
        drawn_ = false;
    }

  private:
    void draw(double fraction, const std::string& count) {
        constexpr int kWidth = 30;
        const double done = std::min(1.0, fraction);
        const int filled = static_cast<int>(done * kWidth);
        fmt::print(stderr, "\r[{:=<{}}{: <{}}] {:3.0f}% {}", "", filled, "", kWidth - filled,
                   100.0 * done, count);
        std::fflush(stderr);
        drawn_ = true;
    }

    std::array<int, 3> xyz_{0, 1, 2};
    std::chrono::steady_clock::time_point last_draw_{};
    bool drawn_ = false;
};

class RunCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.add_option("PROGRAM", program_,
                       "NC program (DIN 66025, or Heidenhain Klartext), or - to read standard "
                       "input")
            ->required();
        inputs_.declare(app);
        app.add_option("--svg", svg_,
                       "Write a plot of the programmed contour and the tool path (- for standard "
                       "output)");
        app.add_option("--json", json_,
                       "Write the executed path, errors and registers as JSON (- for standard "
                       "output)");
        app.add_option("--csv", csv_,
                       "Write the axis positions of every interpolation cycle (- for standard "
                       "output)");
        app.add_flag("--svg-cycles", svg_cycles_,
                     "Draw the axes of every interpolation cycle in the plot too (the OTC offsets "
                     "show there, not in the segments)");
        plane_option_ = app.add_option("--plane", plane_text_,
                       "Draw the plot in this plane (17, 18, 19) instead of "
                       "the program's")
            ->type_name("INT");
        app.add_option("--self-approach", self_approach_,
                       "Where the compensated path comes closer than the tool radius to the "
                       "contour away from its corners (the contour comes back near itself): "
                       "warn (default), error (the run fails there) or off")
            ->check(CLI::IsMember({"warn", "error", "off"}));
        bottleneck_option_ = app.add_option("--avoid-bottlenecks", bottleneck_text_,
                       "Leave out the moves between two compensated moves whose tool paths "
                       "cross, looking this many moves back (2..64, as SINUMERIK's CDON with MD "
                       "20240), and warn 'Bottleneck'; 0 (the default): never")
            ->type_name("N");
        app.add_flag("--one-thread", one_thread_,
                     "Run the NC front end, the board and the writers on this one thread (for "
                     "debugging: the same outputs, byte for byte)");
        app.add_option("--tools-out", tools_out_,
                       "Write the tool list as the run left it (the OTC wear folded in at tool "
                       "change, [ISG-OTC] section 2.9; - for standard output)");
        app.footer(
            "Validates the whole program first: a program that does not parse runs nothing and "
            "its error names file:line:column (on the embedded emulator while it runs, "
            "publishing no output unless it is valid). Then every block drives the board (spooled "
            "profiles tagged with the block number, TC objects for D, G17-G19, G25/G26, "
            "G40-G42) and a summary is printed: blocks, path length, time, errors by name. "
            "Coordinates in the JSON, the plot and the summary are the tool centre point in mm; "
            "the CSV's are the machine's axes (the tool length included). Exit 0 ok, 1 board or "
            "program error (the run stops at the first board error) or an output whose writing "
            "failed, 2 usage (bad option, unreadable program, output file that cannot be "
            "created). Outputs are written to "
            "temporary files beside them and replace them only when the whole run was written; "
            "with an output on standard output (-) the summary goes to standard error. A "
            "program on standard input may be at most 64 MiB. See docs/apcictl.md.");
    }

    Outcome prepare() override {
        // The plot's options without a plot would be taken and do nothing.
        for (const auto& [option, given] :
             {std::pair{"--svg-cycles", svg_cycles_}, std::pair{"--plane", plane_option_->count() > 0}})
            if (given && svg_.empty())
                return Outcome::usage_error(fmt::format(
                    "run: {} is an option of the plot: give --svg FILE too", option));
        if (plane_option_->count() > 0) {
            std::int64_t plane = 0;
            if (!parse_integer("--plane", plane_text_, 17, 19, plane).empty())
                return Outcome::usage_error(
                    fmt::format("run: --plane '{}' is not 17, 18 or 19", plane_text_));
            plane_ = static_cast<int>(plane);
        }
        if (bottleneck_option_->count() > 0) {
            // 0 (never) or 2..64: looking one move back finds nothing, a move's neighbour
            // shares its corner.
            constexpr std::int64_t kMax = apci::run::ProgramExecutor::kMaxBottleneckBlocks;
            std::int64_t blocks = 0;
            if (!parse_integer("--avoid-bottlenecks", bottleneck_text_, 0, kMax, blocks).empty() ||
                blocks == 1)
                return Outcome::usage_error(fmt::format(
                    "run: --avoid-bottlenecks '{}' is not 0 (never) or a number of moves to look "
                    "back, 2..{}",
                    plain_text(bottleneck_text_), kMax));
            bottleneck_blocks_ = static_cast<int>(blocks);
        }
        return refuse_output_over_input();
    }

    Outcome run(Session& session) override {
        apci::run::RunInputs inputs;
        if (Outcome o = load_inputs(inputs); !o.ok()) return o;
        Outcome failure;
        apci::Board* board = session.board(failure);
        if (board == nullptr) return failure;
        // The board's motion is this run's until it ends: another program's moves cannot
        // interleave with its own, and a second run is refused before it moves anything.
        if (Outcome o = session.claim_motion("run"); !o.ok()) return o;

        // Outputs, declared before the writers (which go first).
        RunOutputFiles files(json_, svg_, csv_, tools_out_);
        Outputs outputs;
        // On the embedded emulator, where the process may use two CPUs, this thread (executor
        // and board) keeps one and the two helper threads below share the other
        // (cpu_placement.h); declared first, so the helpers end before it goes (it goes as
        // soon as the run has ended).
        std::optional<apci::run::CpuPlacement> placement;
        if (apci::run::embedded_emulator(session.uri()) && !one_thread_) placement.emplace();
        const apci::run::CpuPlacement* const cpus = placement ? &*placement : nullptr;
        // The front end reads ahead on a thread of its own and the writers run on another, fed
        // in order through a bounded ring (pipeline.h; not with --one-thread); declared after
        // `outputs`, so the threads end before they go.
        apci::run::ProgramRun program(*board, outputs, inputs,
                                      settings(cpus, apci::run::embedded_emulator(session.uri())));

        if (Outcome o = open_program(apci::run::embedded_emulator(session.uri()), files, program); !o.ok())
            return o;
        if (Outcome o = open_outputs(files, program); !o.ok()) return o;
        if (Outcome o = attach_writers(files, program, outputs); !o.ok()) return o;

        apci::run::RunOutcome result = program.run();  // every event written, threads ended
        // The helpers have ended: this thread gets its CPUs back, and the threads that free
        // the files the outputs replace (run_files.h) run on any of them.
        placement.reset();
        if (Outcome o = count_blocks(program, outputs, result); !o.ok()) return o;
        const std::string written_error = write_outputs(files, outputs, result);
        return report(files, result, written_error);
    }

  private:
    // The outputs' files: temporary files beside their targets, renamed over them at the end
    // only if every output was written (run_files.h).
    struct RunOutputFiles {
        enum : std::size_t { kJson, kSvg, kCsv, kToolsOut };
        RunOutputFiles(const std::string& json_target, const std::string& svg_target,
                       const std::string& csv_target, const std::string& tools_target)
            : named{{{&json, &json_target},
                     {&svg, &svg_target},
                     {&csv, &csv_target},
                     {&tools_out, &tools_target}}} {}
        OutputFile json, svg, csv, tools_out;
        const std::array<std::pair<OutputFile*, const std::string*>, 4> named;
    };

    // The tool list (without one, D n (n > 0) is refused by the validation pass), the
    // correction table (without one, FUNCTION CORRDATA TCS #n is refused: the table defines
    // no row), the PLC script; and a program that cannot be read twice, read into memory.
    Outcome load_inputs(apci::run::RunInputs& in) {
        if (Outcome o = inputs_.load(in); !o.ok()) return o;
        if (program_ == "-" || !seekable(program_)) {
            const int fd =
                program_ == "-" ? STDIN_FILENO : ::open(program_.c_str(), O_RDONLY | O_CLOEXEC);
            if (fd < 0)
                return Outcome::usage_error(
                    fmt::format("run: cannot read {}: {}", program_, std::strerror(errno)));
            const std::string why = read_whole_program(fd, program_, stdin_text_);
            if (fd != STDIN_FILENO) ::close(fd);
            if (!why.empty()) return Outcome::usage_error("run: " + why);
            program_in_memory_ = true;
        }
        return Outcome::success();
    }

    // The options of the command line that the run takes. The NC front end reads ahead on a
    // thread of its own (read_ahead.h) and the writers run on another (pipeline.h): the same
    // events, errors and variable reads, the program parsed and the outputs written while the
    // board runs; --one-thread keeps everything on this one.
    apci::run::RunSettings settings(const apci::run::CpuPlacement* cpus, bool embedded) const {
        apci::run::RunSettings s;
        s.threads = !one_thread_;
        s.cpus = cpus;
        // CLI::IsMember let only the mode names through.
        s.self_approach = apci::run::self_approach_mode(self_approach_)
                              .value_or(apci::run::SelfApproachMode::kWarn);
        s.bottleneck_blocks = bottleneck_blocks_;
        // A finding of --self-approach error stops a run on another board only once it moved:
        // there the program runs first on an embedded emulator set up as the board stands.
        s.dry_run_first = !embedded;
        return s;
    }

    apci::run::ProgramSource source() const {
        return program_in_memory_ ? apci::run::ProgramSource::in_memory(stdin_text_, program_name())
                                  : apci::run::ProgramSource::file(program_);
    }

    // The embedded emulator's board is this process's alone and every output is held back
    // in a temporary file until the end: there the program is validated while it runs (one
    // pass), and an invalid one gives the error it gives below and publishes nothing.
    // Elsewhere (a daemon's board, a real one) nothing moves before the program is valid.
    Outcome open_program(bool embedded, const RunOutputFiles& files,
                         apci::run::ProgramRun& program) const {
        bool one_pass = embedded;
        for (auto [out, name] : files.named) one_pass = one_pass && held_back(*name);
        const auto refused =
            one_pass ? program.open_one_pass(source()) : program.open_validated(source());
        return refused ? nc_failure(*refused) : Outcome::success();
    }

    // A failure to set up an output in the one pass: a program that does not validate says so
    // first, as when it is validated before the outputs are opened.
    static Outcome validate_before(Outcome failure, apci::run::ProgramRun& program) {
        if (const auto refused = program.validate_first()) return nc_failure(*refused);
        return failure;
    }

    static Outcome open_outputs(RunOutputFiles& files, apci::run::ProgramRun& program) {
        for (auto [out, name] : files.named) {
            if (name->empty()) continue;
            if (std::string why = out->open(*name); !why.empty())
                return validate_before(
                    Outcome::usage_error(fmt::format("run: cannot write {}: {}", *name, why)),
                    program);
            // Written in place after all (it became a FIFO meanwhile): validated first.
            if (program.one_pass() && !out->is_stdout() && out->temporary().empty())
                if (const auto refused = program.validate_first()) return nc_failure(*refused);
        }
        return Outcome::success();
    }

    // The writers of the outputs opened, and what the progress bar counts.
    Outcome attach_writers(const RunOutputFiles& files, apci::run::ProgramRun& program,
                           Outputs& outputs) const {
        if (files.json.file() != nullptr)
            outputs.json = std::make_unique<apci::run::JsonRunWriter>(files.json.file());
        if (files.svg.file() != nullptr) {
            outputs.svg = std::make_unique<apci::run::SvgPlotWriter>();
            if (!outputs.svg->ok())
                return validate_before(
                    Outcome::board_error("run: cannot make a temporary file for the plot"),
                    program);
        }
        outputs.csv_file = files.csv.file();
        outputs.svg_cycles = svg_cycles_;
        outputs.one_pass = program.one_pass();
        outputs.program_bytes = program.program_bytes();
        outputs.total_blocks = program.validated_blocks();
        outputs.progress_bar = ::isatty(STDERR_FILENO) == 1;
        return Outcome::success();
    }

    // The program's block count and name in the totals. In one pass, the rest of the program
    // (after an error stopped the run) is validated too; an invalid program publishes
    // nothing: the outputs are removed on return.
    static Outcome count_blocks(apci::run::ProgramRun& program, Outputs& outputs,
                                apci::run::RunOutcome& result) {
        const bool one_pass = program.one_pass();
        if (const auto refused = program.finish(result)) {
            outputs.clear_progress();
            return nc_failure(*refused);
        }
        if (one_pass) outputs.completed(result.totals.blocks);
        outputs.clear_progress();
        return Outcome::success();
    }

    // The writers finish; every output is closed (its last bytes written, synced), and only
    // when all of them are complete are they renamed over their targets, together. Empty
    // when every output was published, else why not.
    std::string write_outputs(RunOutputFiles& files, Outputs& outputs,
                              const apci::run::RunOutcome& result) const {
        const std::array<bool, 4> failed = finish_writers(files, outputs, result);
        // A run the board stopped with an error is finished: its outputs say so and are
        // published. One that lost its board (the link failed: the daemon was killed, the
        // board unplugged) or its host's memory did not finish: nothing of it is published
        // over the old outputs (docs/apcictl.md, "Outputs").
        std::string written_error;
        if (const RunError* lost = link_failure(result.errors))
            written_error = unfinished_run(result.totals.file, *lost);
        for (std::size_t i = 0; i < files.named.size(); ++i) {
            // The output's own record of its first failed write names the cause; the plot
            // can fail reading back its temporary records too.
            const std::string why = files.named[i].first->close();
            if (!written_error.empty() || (!failed[i] && why.empty())) continue;
            const char* other = i == RunOutputFiles::kSvg
                                    ? "the plot's temporary records could not be read back"
                                    : "the write failed";
            written_error = fmt::format("run: cannot write {}: {}", *files.named[i].second,
                                        why.empty() ? std::string(other) : why);
        }
        if (written_error.empty()) {
            const apci::run::DeferSignals together;
            for (auto [out, name] : files.named) {
                if (std::string why = out->publish(); !why.empty()) {
                    written_error = fmt::format("run: cannot write {}: {}", *name, why);
                    break;
                }
            }
        }
        for (auto [out, name] : files.named) out->discard();  // an output not published is removed
        return written_error;
    }

    // Each writer's last bytes; true where one failed.
    std::array<bool, 4> finish_writers(const RunOutputFiles& files, Outputs& outputs,
                                       const apci::run::RunOutcome& result) const {
        std::array<bool, 4> failed{};
        if (outputs.json)
            failed[RunOutputFiles::kJson] =
                !outputs.json->finish(result.errors, result.registers, result.variables,
                                      result.notices, result.warnings);
        if (files.tools_out.file() != nullptr) {
            const std::string text = apci::nc::format_tool_table(result.tools_after);
            failed[RunOutputFiles::kToolsOut] =
                std::fwrite(text.data(), 1, text.size(), files.tools_out.file()) != text.size();
        }
        if (outputs.svg)
            failed[RunOutputFiles::kSvg] = !outputs.svg->finish(
                files.svg.file(), plane_ != 0 ? plane_ : result.plot_plane, result.totals.file);
        if (outputs.csv) failed[RunOutputFiles::kCsv] = !outputs.csv->finish();
        outputs.json.reset();
        outputs.csv.reset();
        return failed;
    }

    // The summary, warnings and notices (on standard error when an output is standard
    // output: "-", or a name of it, /dev/stdout, /dev/fd/1), and the command's outcome.
    static Outcome report(const RunOutputFiles& files, const apci::run::RunOutcome& result,
                          const std::string& written_error) {
        std::FILE* summary_to = stdout;
        for (auto [out, name] : files.named)
            if (out->is_stdout() || names_standard_output(*name)) summary_to = stderr;
        apci::run::print_summary(summary_to, result.totals, result.errors);
        print_warnings_and_notices(summary_to, result);
        std::fflush(summary_to);
        if (!result.errors.empty() && !written_error.empty())
            fmt::print(stderr, "apcictl: {}\n", written_error);
        if (!result.errors.empty()) {
            return Outcome::board_error(stopped_run(result.totals.file, result.errors.front()));
        }
        if (!written_error.empty()) return Outcome::board_error(written_error);
        return Outcome::success();
    }
    // An output that is an input (the program, --tools, --plc, --corr) or another output would
    // overwrite it or mix two outputs in one file: refused before anything runs. The same file:
    // the same path once absolute and normalised, or (when both exist) the same device and
    // inode, so a symlink or a hard link to an input is caught too.
    Outcome refuse_output_over_input() const {
        std::vector<std::pair<std::string_view, const std::string*>> files;
        if (program_ != "-") files.emplace_back("PROGRAM", &program_);
        for (const auto& input : inputs_.named()) files.push_back(input);
        const std::size_t inputs = files.size();
        files.emplace_back("--json", &json_);
        files.emplace_back("--svg", &svg_);
        files.emplace_back("--csv", &csv_);
        files.emplace_back("--tools-out", &tools_out_);
        // "-" is standard output: one output at most, and no file to compare.
        std::size_t on_stdout = 0;
        for (std::size_t out = inputs; out < files.size(); ++out) {
            if (*files[out].second != "-") continue;
            if (on_stdout != 0)
                return Outcome::usage_error(fmt::format(
                    "run: {} and {} both write to standard output (-); give one of them a file",
                    files[on_stdout].first, files[out].first));
            on_stdout = out;
        }
        for (std::size_t out = inputs; out < files.size(); ++out) {
            if (files[out].second->empty() || *files[out].second == "-") continue;
            for (std::size_t other = 0; other < out; ++other) {
                if (files[other].second->empty()) continue;
                if (!apci::run::same_file(*files[out].second, *files[other].second)) continue;
                return Outcome::usage_error(
                    fmt::format("run: {} '{}' is the same file as {} '{}' ({})", files[out].first,
                                *files[out].second, files[other].first, *files[other].second,
                                other < inputs ? "the output would overwrite the input"
                                               : "the two outputs would be mixed in one file"));
            }
        }
        return Outcome::success();
    }

    std::string program_;
    RunInputOptions inputs_;
    std::string svg_;
    std::string json_;
    std::string csv_;
    std::string tools_out_;
    std::string self_approach_ = "warn";
    std::string bottleneck_text_;
    const CLI::Option* bottleneck_option_ = nullptr;
    const CLI::Option* plane_option_ = nullptr;
    int bottleneck_blocks_ = 0;
    bool svg_cycles_ = false;
    bool one_thread_ = false;
    std::string plane_text_;
    int plane_ = 0;
    // The name the program goes by in messages and outputs.
    std::string program_name() const { return program_ == "-" ? "<stdin>" : program_; }

    std::string stdin_text_;  // the program of "-", or of a file that is not seekable
    bool program_in_memory_ = false;
};

}  // namespace

std::unique_ptr<Command> make_run_command() {
    return std::make_unique<RunCommand>();
}

}  // namespace apcictl
