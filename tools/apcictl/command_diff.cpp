// SPDX-License-Identifier: MIT
// `diff --against URI PROGRAM`: the hardware-in-loop mode (docs/design.md section
// 7). Runs the same work on the --device board and on the --against board
// (typically a real board and emu:) and reports the first thing that differs:
//  - a script (apcictl script syntax): each line runs on both boards in turn;
//    the first line whose printed result or failure differs is reported with
//    its line number;
//  - an NC program (*.nc, Klartext *.h, or --nc): `run` on both boards (with
//    --tools, --corr and --plc as `run` takes them), recording every
//    interpolation cycle's axis positions, the executed segments, the errors
//    and the TC registers at the end; the first difference is reported, in
//    this order: start position, a position in a cycle both runs had (with
//    its block and cycle), an error, the length of the run, a TC register
//    bit at the end, an executed segment.
// Exit 0: no difference; 1: a difference, or a board or program error; 2: usage.
#include <fmt/format.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "apci/nc/diagnostic.h"
#include "apci/run/executor.h"
#include "apci/run/json_writer.h"
#include "apci/run/program_run.h"
#include "apci/run/run_files.h"
#include "arguments.h"
#include "command.h"
#include "object_name.h"
#include "objif/map/object_map.h"
#include "run_inputs.h"

namespace apcictl {
namespace {

using apci::run::BlockRef;
using apci::run::OutputFile;
using apci::run::PathSegment;
using apci::run::RunError;

// The first thing that differs between the two runs.
struct Difference {
    std::string where;  // "line 3", "N40, cycle 1234"
    std::string what;   // "read 1300 1 1 7", "axis X position"
    std::string here;   // on --device
    std::string there;  // on --against
};

// Everything a command prints on stdout while it runs, for comparison.
class StdoutCapture {
  public:
    StdoutCapture() {
        std::fflush(stdout);
        fd_ = ::memfd_create("apcictl-diff", MFD_CLOEXEC);
        saved_ = ::dup(STDOUT_FILENO);
        if (fd_ >= 0 && saved_ >= 0) ::dup2(fd_, STDOUT_FILENO);
    }
    ~StdoutCapture() { finish(); }
    StdoutCapture(const StdoutCapture&) = delete;
    StdoutCapture& operator=(const StdoutCapture&) = delete;

    std::string finish() {
        if (saved_ < 0) return text_;
        std::fflush(stdout);
        ::dup2(saved_, STDOUT_FILENO);
        ::close(saved_);
        saved_ = -1;
        if (fd_ >= 0) {
            char buffer[4096];
            ssize_t n = 0;
            ::lseek(fd_, 0, SEEK_SET);
            while ((n = ::read(fd_, buffer, sizeof buffer)) > 0)
                text_.append(buffer, static_cast<std::size_t>(n));
            ::close(fd_);
            fd_ = -1;
        }
        return text_;
    }

  private:
    int fd_ = -1;
    int saved_ = -1;
    std::string text_;
};

// What one script line did on one board: its output, or why it failed.
std::string line_result(Command& command, Session& session) {
    StdoutCapture capture;
    const Outcome outcome = command.run(session);
    std::string printed = capture.finish();
    if (!printed.empty() && printed.back() == '\n') printed.pop_back();
    if (outcome.ok()) return printed;
    return printed.empty() ? "failed: " + outcome.error : printed + "\nfailed: " + outcome.error;
}

// A script line as typed; with the object it reads or writes named, where the map names it:
// "read 1300 1 1 7, object tc.group[1].radius (1300/1/1/7)".
std::string line_what(const ScriptLine& line) {
    const std::optional<objif::Address> a = line.command->object();
    if (!a || objif::find_object(*a) == nullptr) return line.text;
    return fmt::format("{}, object {}", line.text, object_label(*a));
}

Outcome diff_script(const std::string& file, Session& here, Session& there,
                    std::optional<Difference>& first, std::size_t& compared) {
    std::vector<ScriptLine> lines;
    if (Outcome read = read_script(file, lines); !read.ok()) return read;
    for (auto& line : lines) {
        ++compared;
        std::string a = line_result(*line.command, here);
        std::string b = line_result(*line.command, there);
        if (a != b) {
            first = Difference{fmt::format("line {}", line.number), line_what(line), std::move(a),
                               std::move(b)};
            return Outcome::success();
        }
    }
    return Outcome::success();
}

// ---- NC programs

// Fixed-size records in an unnamed temporary file (tmpfile(3): gone however the process
// ends), written in large pieces and read back in order: a run of any length is compared in
// the same memory.
template <typename Record>
class Spool {
  public:
    static_assert(std::is_trivially_copyable_v<Record>);
    Spool() : file_(std::tmpfile()) {
        if (file_ == nullptr) {
            error_ = errno != 0 ? errno : EIO;
            return;
        }
        std::setvbuf(file_, nullptr, _IOFBF, std::size_t{1} << 16);
    }
    ~Spool() {
        if (file_ != nullptr) std::fclose(file_);
    }
    Spool(const Spool&) = delete;
    Spool& operator=(const Spool&) = delete;

    void push(const Record& r) {
        if (error_ != 0) return;
        if (std::fwrite(&r, sizeof r, 1, file_) != 1) {
            error_ = errno != 0 ? errno : EIO;
            return;
        }
        ++size_;
    }
    // Reads from the first record again.
    void rewind() {
        read_ = 0;
        if (error_ == 0 && (std::fflush(file_) != 0 || std::fseek(file_, 0, SEEK_SET) != 0))
            error_ = errno != 0 ? errno : EIO;
    }
    // The next record; false at the end or on an error.
    bool next(Record& r) {
        if (error_ != 0 || read_ >= size_) return false;
        if (std::fread(&r, sizeof r, 1, file_) != 1) {
            error_ = errno != 0 ? errno : EIO;
            return false;
        }
        ++read_;
        return true;
    }
    std::uint64_t size() const noexcept { return size_; }
    int error() const noexcept { return error_; }

  private:
    std::FILE* file_;
    std::uint64_t size_ = 0;
    std::uint64_t read_ = 0;
    int error_ = 0;
};

struct Sample {
    std::uint64_t cycle = 0;
    std::array<double, APCI_AXIS_COUNT> position{};
};

// What the comparison needs of an executed segment.
struct SegmentRecord {
    std::int64_t number = 0;
    std::uint64_t line = 0;
    apci::run::SegmentKind kind = apci::run::SegmentKind::kLine;
    apci::run::Role role = apci::run::Role::kUncompensated;
    std::array<double, 3> start{};
    std::array<double, 3> end{};
    std::uint64_t start_cycle = 0;
    std::uint64_t end_cycle = 0;

    BlockRef block() const { return BlockRef{number, line}; }
};

SegmentRecord segment_record(const PathSegment& s) {
    SegmentRecord r;
    r.number = s.block.number;
    r.line = s.block.line;
    r.kind = s.kind;
    r.role = s.role;
    for (int i = 0; i < 3; ++i) {
        r.start[static_cast<std::size_t>(i)] = s.start[i];
        r.end[static_cast<std::size_t>(i)] = s.end[i];
    }
    r.start_cycle = s.start_cycle;
    r.end_cycle = s.end_cycle;
    return r;
}

Sample sample_of(std::uint64_t cycle, std::span<const double> axes) {
    Sample s;
    s.cycle = cycle;
    std::copy_n(axes.begin(), std::min(axes.size(), s.position.size()), s.position.begin());
    return s;
}

// What `run` did on one board: the executed segments spooled, the rest (errors, registers:
// a few each) in memory.
struct Recording : apci::run::RunSink {
    Spool<SegmentRecord> segments;
    // --json: the run as `run --json` writes it (the first run only).
    apci::run::JsonRunWriter* json = nullptr;
    std::vector<std::string> axis_names;
    apci::run::Point start = apci::run::Point::Zero();  // X, Y, Z where the run began
    apci::run::RunOutcome outcome;
    std::uint64_t samples = 0;

    void executed(const PathSegment& s) override {
        segments.push(segment_record(s));
        if (json != nullptr) json->segment(s);
    }
    bool wants_samples() const override { return true; }
    void axes(std::span<const std::string> names) override {
        axis_names.assign(names.begin(), names.end());
    }

    // The block whose segment ran in `cycle`.
    std::string block_at(std::uint64_t cycle) {
        segments.rewind();
        SegmentRecord s;
        while (segments.next(s))
            if (s.start_cycle < cycle && cycle <= s.end_cycle)
                return apci::run::block_text(s.block());
        return "no block";
    }
};

// The first run (--device): its positions cycle by cycle go to a spool.
struct FirstRun final : Recording {
    Spool<Sample> positions;
    void sample(std::uint64_t cycle, double, std::span<const double> axes) override {
        positions.push(sample_of(cycle, axes));
        ++samples;
    }
};

// The first place two runs' positions differ, as found cycle by cycle.
struct SampleDifference {
    std::uint64_t index = 0;        // 0: the first sample of the run
    std::uint64_t first_cycle = 0;  // the first run's clock there
    std::size_t axis = 0;
    double here = 0.0;
    double there = 0.0;
};

// The second run (--against): each cycle is compared with the first run's at once (cycles count
// from the start of the run: the boards' clocks need not agree, a daemon's board has run
// before), so neither run's cycles are kept.
struct SecondRun final : Recording {
    SecondRun(Spool<Sample>& first, double tolerance) : first_(first), tolerance_(tolerance) {
        first_.rewind();
    }
    std::optional<SampleDifference> difference;
    // The clock of this run's first cycle that the first run did not have.
    std::optional<std::uint64_t> first_cycle_beyond;

    void sample(std::uint64_t cycle, double, std::span<const double> axes) override {
        const std::uint64_t index = samples++;
        Sample x;
        if (!first_.next(x)) {
            if (!first_cycle_beyond) first_cycle_beyond = cycle;
            return;
        }
        if (difference) return;
        const Sample y = sample_of(cycle, axes);
        for (std::size_t axis = 0; axis < x.position.size(); ++axis) {
            if (std::abs(x.position[axis] - y.position[axis]) <= tolerance_) continue;
            difference = SampleDifference{index, x.cycle, axis, x.position[axis], y.position[axis]};
            return;
        }
    }

  private:
    Spool<Sample>& first_;
    double tolerance_;
};

// One run of the program on one board, validated first, as `run` runs it (program_run.h); the
// inputs are loaded once for both runs.
Outcome record_run(const std::string& path, const apci::run::RunInputs& in, Session& session,
                   Recording& out) {
    Outcome failure;
    apci::Board* board = session.board(failure);
    if (board == nullptr) return failure;
    apci::run::ProgramRun program(*board, out, in, apci::run::RunSettings{});
    out.start = program.options().start_position;
    if (auto refused = program.open_validated(apci::run::ProgramSource::file(path)))
        return nc_failure(*refused);
    out.outcome = program.run();
    if (auto refused = program.finish(out.outcome)) return nc_failure(*refused);
    return Outcome::success();
}

std::string number(double v) {
    return fmt::format("{}", v);
}

std::string error_text(const RunError& e) {
    return fmt::format("{} at {}: {}", e.code, apci::run::block_text(e.block), e.message);
}

std::string registers_text(std::int32_t error, std::int32_t status) {
    std::string errors;
    for (int bit = 0; bit < 8; ++bit) {
        if ((error & (1 << bit)) == 0) continue;
        const char* name = apci_tc_error_bit_name(bit);
        errors += fmt::format("{}{}", errors.empty() ? "" : "|", name != nullptr ? name : "?");
    }
    return fmt::format("ERROR {:#04x} ({}), STATUS {:#04x}", error,
                       errors.empty() ? "none" : errors, status);
}

// Positions cycle by cycle (found while the second run went, SecondRun).
std::optional<Difference> compare_samples(FirstRun& a, const SecondRun& b) {
    if (!b.difference) return std::nullopt;
    const SampleDifference& d = *b.difference;
    const std::string name =
        d.axis < a.axis_names.size() ? a.axis_names[d.axis] : fmt::format("a{}", d.axis);
    return Difference{fmt::format("{}, cycle {}", a.block_at(d.first_cycle), d.index + 1),
                      fmt::format("axis {} position", name), number(d.here), number(d.there)};
}

// One run went on after the other stopped (compared after the errors, which
// usually say why).
std::optional<Difference> compare_length(FirstRun& a, SecondRun& b) {
    if (a.samples == b.samples) return std::nullopt;
    const std::uint64_t n = std::min(a.samples, b.samples);
    std::string block;
    if (a.samples > b.samples) {
        // The first run's cycle n is the next one the second run did not read.
        Sample s;
        block = a.positions.next(s) ? a.block_at(s.cycle) : "no block";
    } else {
        block = b.first_cycle_beyond ? b.block_at(*b.first_cycle_beyond) : "no block";
    }
    const auto ran = [](const Recording& r) {
        return fmt::format("the run took {} cycles", r.samples);
    };
    return Difference{fmt::format("{}, cycle {}", block, n + 1), "length of the run", ran(a),
                      ran(b)};
}

std::optional<Difference> compare_start(const Recording& a, const Recording& b, double tolerance) {
    for (int i = 0; i < 3; ++i) {
        if (std::abs(a.start[i] - b.start[i]) <= tolerance) continue;
        return Difference{"the start of the run",
                          fmt::format("axis {} position", apci::run::axis_letter(i)),
                          number(a.start[i]), number(b.start[i])};
    }
    return std::nullopt;
}

std::optional<Difference> compare_errors(const Recording& a, const Recording& b) {
    const auto& x = a.outcome.errors;
    const auto& y = b.outcome.errors;
    for (std::size_t i = 0; i < std::max(x.size(), y.size()); ++i) {
        const std::string p = i < x.size() ? error_text(x[i]) : "no error";
        const std::string q = i < y.size() ? error_text(y[i]) : "no error";
        const bool same = i < x.size() && i < y.size() && x[i].code == y[i].code &&
                          x[i].block.number == y[i].block.number &&
                          x[i].block.line == y[i].block.line;
        if (!same) {
            const BlockRef& at = i < x.size() ? x[i].block : y[i].block;
            return Difference{apci::run::block_text(at), fmt::format("error {}", i + 1), p, q};
        }
    }
    return std::nullopt;
}

std::optional<Difference> compare_registers(const Recording& a, const Recording& b) {
    const auto& x = a.outcome.registers;
    const auto& y = b.outcome.registers;
    if (x.size() != y.size())
        return Difference{"end of the run", "TC module", x.empty() ? "absent" : "present",
                          y.empty() ? "absent" : "present"};
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i].readable == y[i].readable && x[i].error == y[i].error &&
            x[i].status == y[i].status)
            continue;
        // The register that differs, by name: tc.group[1].error (1300/1/1/1).
        const bool error_differs = x[i].readable != y[i].readable || x[i].error != y[i].error;
        const objif::Address reg{
            objif::map::tc::kBus, objif::map::tc::kDevGroups, x[i].group,
            error_differs ? objif::map::tc::kSubError : objif::map::tc::kSubStatus};
        return Difference{
            "end of the run",
            fmt::format("registers of TC group {}: {}", x[i].group, object_label(reg)),
            x[i].readable ? registers_text(x[i].error, x[i].status) : "unreadable",
            y[i].readable ? registers_text(y[i].error, y[i].status) : "unreadable"};
    }
    return std::nullopt;
}

std::string segment_text(const SegmentRecord& s) {
    return fmt::format("{} {} from ({}, {}, {}) to ({}, {}, {})", apci::run::kind_name(s.kind),
                       apci::run::role_name(s.role), s.start[0], s.start[1], s.start[2], s.end[0],
                       s.end[1], s.end[2]);
}

bool same_point(const std::array<double, 3>& p, const std::array<double, 3>& q, double tolerance) {
    for (std::size_t i = 0; i < 3; ++i)
        if (!(std::abs(p[i] - q[i]) <= tolerance)) return false;
    return true;
}

// The executed segments, both spools read side by side.
std::optional<Difference> compare_segments(Recording& a, Recording& b, double tolerance) {
    a.segments.rewind();
    b.segments.rewind();
    for (std::uint64_t i = 0;; ++i) {
        SegmentRecord xs, ys;
        const bool have_x = a.segments.next(xs);
        const bool have_y = b.segments.next(ys);
        if (!have_x && !have_y) break;
        const bool same = have_x && have_y && xs.kind == ys.kind && xs.role == ys.role &&
                          xs.number == ys.number && same_point(xs.end, ys.end, tolerance) &&
                          same_point(xs.start, ys.start, tolerance);
        if (!same) {
            const SegmentRecord& at = have_x ? xs : ys;
            return Difference{
                apci::run::block_text(at.block()), fmt::format("executed segment {}", i + 1),
                have_x ? segment_text(xs) : "none", have_y ? segment_text(ys) : "none"};
        }
    }
    return std::nullopt;
}

// An NC program by its name: *.nc (DIN 66025, ISG) or *.h (Klartext, as TNC controls name them).
bool ends_with_nc(std::string_view path) {
    std::string name(path);
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return name.ends_with(".nc") || name.ends_with(".h");
}

class DiffCommand final : public Command {
  public:
    void declare(CLI::App& app) override {
        app.add_option("PROGRAM", program_,
                       "Script (apcictl script syntax) or NC program (*.nc, Klartext *.h)")
            ->required();
        app.add_option("--against", against_, "The device URI to compare --device with (e.g. emu:)")
            ->required();
        inputs_.declare(app);  // as run takes them; the PLC writes at the same cycles in both
        app.add_option("--json", json_,
                       "NC programs: write the --device board's run as `run --json` writes it "
                       "(replaced only once the run was written whole)");
        app.add_option("--tolerance", tolerance_text_,
                       "NC programs: positions closer than this are equal (program units, a "
                       "finite number >= 0; default 0: bit for bit)")
            ->type_name("FLOAT");
        auto* nc =
            app.add_flag("--nc", force_nc_, "Treat PROGRAM as an NC program whatever its name");
        auto* script =
            app.add_flag("--script", force_script_, "Treat PROGRAM as a script whatever its name");
        nc->excludes(script);
        app.footer(
            "Runs the work on --device and on --against and reports the first difference: for "
            "a script, the first line whose printed result or failure differs; for an NC "
            "program, the first interpolation cycle whose axis positions differ (with its "
            "block), then the first differing error, TC register at the end, or executed "
            "segment. Exit 0 no difference, 1 a difference or a board/program error, 2 usage.");
    }

    Outcome prepare() override {
        if (!tolerance_text_.empty()) {
            if (std::string why = parse_non_negative("--tolerance", tolerance_text_, tolerance_);
                !why.empty())
                return Outcome::usage_error("diff: " + why);
        }
        if (program_ == "-" && is_nc())
            return Outcome::usage_error("diff: an NC program must be a file (it runs twice)");
        if (!json_.empty() && !is_nc())
            return Outcome::usage_error("diff: --json writes an NC program's run; " + program_ +
                                        " is a script");
        if (json_ == "-")
            return Outcome::usage_error(
                "diff: --json needs a file (standard output has the comparison)");
        std::vector<std::pair<std::string_view, const std::string*>> inputs{{"PROGRAM", &program_}};
        for (const auto& input : inputs_.named()) inputs.push_back(input);
        for (const auto& [name, input] : inputs)
            if (!json_.empty() && !input->empty() && apci::run::same_file(json_, *input))
                return Outcome::usage_error(fmt::format(
                    "diff: --json '{}' is the same file as the input {} '{}' (the output would "
                    "overwrite it)",
                    json_, name, *input));
        return Outcome::success();
    }

    Outcome run(Session& session) override {
        Session there(against_);
        // Both boards' motion is the diff's until it ends, as for `run`.
        if (Outcome o = session.claim_motion("diff"); !o.ok()) return o;
        if (Outcome o = there.claim_motion("diff"); !o.ok()) return o;
        std::optional<Difference> first;
        std::size_t compared = 0;
        std::string unit = "script lines";
        Outcome outcome;
        if (is_nc()) {
            outcome = diff_nc(session, there, first, compared);
            unit = "interpolation cycles";
        } else {
            outcome = diff_script(program_, session, there, first, compared);
        }
        if (!outcome.ok()) return outcome;
        if (!first) {
            fmt::print("diff: no difference between {} and {} ({} {} compared)\n", session.uri(),
                       against_, compared, unit);
            return Outcome::success();
        }
        const std::size_t width = std::max(session.uri().size(), against_.size());
        fmt::print("diff: first difference at {}: {}\n", first->where, first->what);
        fmt::print("  {:<{}}  {}\n", session.uri(), width, indented(first->here, width));
        fmt::print("  {:<{}}  {}\n", against_, width, indented(first->there, width));
        return Outcome::board_error(
            fmt::format("diff: {} and {} differ at {}", session.uri(), against_, first->where));
    }

  private:
    bool is_nc() const { return force_nc_ || (!force_script_ && ends_with_nc(program_)); }

    static std::string indented(const std::string& text, std::size_t width) {
        std::string out;
        for (char c : text) {
            out += c;
            if (c == '\n') out += std::string(width + 4, ' ');
        }
        return out.empty() ? "(nothing printed)" : out;
    }

    Outcome diff_nc(Session& here, Session& there, std::optional<Difference>& first,
                    std::size_t& compared) {
        apci::run::RunInputs in;
        if (Outcome o = inputs_.load(in); !o.ok()) return o;
        // The first run spools its positions; the second compares its own with them cycle
        // by cycle as it goes. Memory stays the same however long the runs.
        FirstRun a;
        OutputFile json_file;
        std::optional<apci::run::JsonRunWriter> json;
        if (!json_.empty()) {
            if (std::string why = json_file.open(json_); !why.empty())
                return Outcome::usage_error(fmt::format("diff: cannot write {}: {}", json_, why));
            a.json = &json.emplace(json_file.file());
        }
        if (Outcome o = record_run(program_, in, here, a); !o.ok()) return o;
        a.json = nullptr;  // the first run is over; its writer goes in publish_json()
        if (json)
            if (Outcome o = publish_json(json, json_file, a.outcome); !o.ok()) return o;
        SecondRun b(a.positions, tolerance_);
        if (Outcome o = record_run(program_, in, there, b); !o.ok()) return o;
        compared = std::min(a.samples, b.samples);
        first = compare_start(a, b, tolerance_);
        if (!first) first = compare_samples(a, b);
        if (!first) first = compare_errors(a, b);
        if (!first) first = compare_length(a, b);
        if (!first) first = compare_registers(a, b);
        if (!first) first = compare_segments(a, b, tolerance_);
        for (const int error : {a.positions.error(), a.segments.error(), b.segments.error()})
            if (error != 0)
                return Outcome::board_error(
                    fmt::format("diff: cannot keep the runs' cycles in a temporary file: {}",
                                std::strerror(error)));
        return Outcome::success();
    }

    // The first run's JSON finished, closed and renamed over its target. The writer goes
    // before its file is closed: its destructor flushes the FILE it was given (left to the
    // end of diff_nc, it flushed a FILE closed here: glibc aborted or the run crashed).
    Outcome publish_json(std::optional<apci::run::JsonRunWriter>& json, OutputFile& file,
                         const apci::run::RunOutcome& run) const {
        const bool written =
            json->finish(run.errors, run.registers, run.variables, run.notices, run.warnings);
        json.reset();
        std::string why = file.close();
        if (why.empty() && !written) why = "the write failed";
        if (why.empty()) why = file.publish();
        if (why.empty()) return Outcome::success();
        return Outcome::board_error(fmt::format("diff: cannot write {}: {}", json_, why));
    }

    std::string program_;
    std::string against_;
    std::string json_;
    RunInputOptions inputs_;
    std::string tolerance_text_;
    double tolerance_ = 0.0;
    bool force_nc_ = false;
    bool force_script_ = false;
};

}  // namespace

std::unique_ptr<Command> make_diff_command() {
    return std::make_unique<DiffCommand>();
}

}  // namespace apcictl
