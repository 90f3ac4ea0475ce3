// SPDX-License-Identifier: MIT
// apci._apci: the extension module under the Python package apci (docs/python.md). A thin layer
// over libapci's public API (apci.hpp) and the executor of `apcictl run` (apci_run): it answers
// status codes and plain values; the package's Python code turns them into exceptions, enums and
// NumPy record arrays. Nothing here raises for a board's refusal.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "apci/apci.hpp"
#include "apci/nc/diagnostic.h"
#include "apci/run/board_words.h"
#include "apci/run/executor.h"
#include "apci/run/path.h"
#include "apci/run/program_run.h"
#include "apci/run/summary.h"
#include "objif/descriptor.h"
#include "objif/names.h"
#include "objif/object_info.h"
#include "objif/value.h"

namespace py = pybind11;

namespace {

// What a Python program does to open a lost link again, in the words of a lost link (the
// board's last_error and a run's errors): a Python Board is not reopened by its next call.
constexpr std::string_view kLostLinkHint = "apci.open() opens the board again";

// ---- Boards

// An open board for Python: apci::Board plus close(). A board is used from one thread at a time
// (apci.h): every call holds the board's lock, and a call from another thread while one runs
// (a program in apci.run, whose thread lets the GIL go) is refused with RuntimeError instead of
// racing it.
class PyBoard {
  public:
    explicit PyBoard(const std::string& uri) : board_(uri), uri_(uri) {}

    bool is_open() const noexcept { return board_.is_open(); }
    apci::Status open_status() const noexcept { return board_.open_status(); }
    // libapci's words; a lost link's end with the module's hint instead of apci_reconnect()
    // (a Python Board is not reopened: apci.open() opens the board again).
    std::string last_error() const {
        return apci::run::board_words(board_, kLostLinkHint);
    }
    const std::string& uri() const noexcept { return uri_; }
    void close() {
        const Use use(*this);
        board_ = apci::Board();
    }

    std::tuple<apci::Status, std::int32_t> read_int(std::int32_t bus, std::int32_t device,
                                                    std::int32_t index, std::int32_t subindex) {
        const Use use(*this);
        auto o = apci::object(bus, device, index, subindex);
        const auto r = board_.read_int(o);
        return {r.status, r.ok() ? r.value : 0};
    }
    std::tuple<apci::Status, double> read_double(std::int32_t bus, std::int32_t device,
                                                 std::int32_t index, std::int32_t subindex) {
        const Use use(*this);
        auto o = apci::object(bus, device, index, subindex);
        const auto r = board_.read_double(o);
        return {r.status, r.ok() ? r.value : 0.0};
    }
    apci::Status write_int(std::int32_t bus, std::int32_t device, std::int32_t index,
                           std::int32_t subindex, std::int32_t value) {
        const Use use(*this);
        auto o = apci::object(bus, device, index, subindex);
        return board_.write_int(o, value).status;
    }
    apci::Status write_double(std::int32_t bus, std::int32_t device, std::int32_t index,
                              std::int32_t subindex, double value) {
        const Use use(*this);
        auto o = apci::object(bus, device, index, subindex);
        return board_.write_double(o, value).status;
    }

    // The board's motion (docs/motion-claim.md): claim, release, and who holds it as (status,
    // held, yours, pid, since_ms, name, holder), the holder as libapci names it in a refusal
    // (apci_motion_claim_holder; "" when free).
    apci::Status claim_motion() {
        const Use use(*this);
        return board_.claim_motion().status;
    }
    apci::Status release_motion() {
        const Use use(*this);
        return board_.release_motion().status;
    }
    std::tuple<apci::Status, bool, bool, std::int32_t, std::uint64_t, std::string, std::string>
    motion_claim() {
        const Use use(*this);
        const auto r = board_.motion_claim();
        if (!r.ok()) return {r.status, false, false, 0, 0, {}, {}};
        const apci_motion_claim& c = r.value;
        return {r.status,   c.held != 0, c.yours != 0, c.pid, c.since_ms,
                apci::motion_claim_name(c), apci::motion_claim_holder(c)};
    }

    // Holds the board for one call, or throws RuntimeError when another thread holds it.
    class Use {
      public:
        explicit Use(PyBoard& b) : lock_(b.mutex_, std::try_to_lock) {
            if (!lock_.owns_lock())
                throw std::runtime_error("board '" + b.uri_ +
                                         "' is in use by another thread (apci.run); a board "
                                         "serves one thread at a time");
        }

      private:
        std::unique_lock<std::mutex> lock_;
    };
    // The board itself, for a caller that holds a Use.
    apci::Board& board(const Use& /*held*/) noexcept { return board_; }

  private:
    apci::Board board_;
    std::string uri_;
    std::mutex mutex_;
};

// Every status code apci.h lists, by the name apci_status_name() gives it.
std::vector<std::pair<std::string, apci::Status>> status_codes() {
    // clang-format off
    static constexpr std::array<apci_status, APCI_STATUS_COUNT> kCodes{
        APCI_OK, APCI_NO_SUCH_DEVICE, APCI_OBJECT_MISSING, APCI_SUB_MISSING, APCI_STALE_HANDLE,
        APCI_HANDLE_MISMATCH, APCI_READ_ONLY, APCI_WRITE_ONLY, APCI_TYPE_MISMATCH,
        APCI_VALUE_TOO_HIGH, APCI_VALUE_TOO_LOW, APCI_INVALID_VALUE, APCI_WRONG_DEVICE_STATE,
        APCI_BUSY, APCI_MOTION_CLAIMED, APCI_GENERAL_ERROR, APCI_BAD_FRAME, APCI_UNKNOWN_OPCODE, APCI_TRANSPORT_ERROR,
        APCI_TIMEOUT, APCI_NOT_SUPPORTED, APCI_INVALID_ARGUMENT, APCI_NO_MEMORY};
    // clang-format on
    std::vector<std::pair<std::string, apci::Status>> out;
    out.reserve(kCodes.size());
    for (const apci_status code : kCodes) out.emplace_back(apci_status_name(code), code);
    return out;
}

// The [APCI-TC] names of the ERROR (Table 4) or STATUS (Table 5) bits: (name, mask) pairs.
std::vector<std::pair<std::string, std::uint32_t>> tc_bits(const char* (*name_of)(int)) {
    std::vector<std::pair<std::string, std::uint32_t>> out;
    for (int bit = 0; bit < 32; ++bit) {
        if (const char* name = name_of(bit)) out.emplace_back(name, std::uint32_t{1} << bit);
    }
    return out;
}

// ---- Object names (objif/names.h): the board's object map by dotted name, shared by the host
// and the emulator, so the type and range the package uses are those the board checks.

// One object of the map as a dict: its name, address and what the map says of it.
py::dict object_dict(const objif::NamedObject& o) {
    py::dict out;
    out["name"] = o.name;
    out["bus"] = o.address.bus;
    out["device"] = o.address.device;
    out["index"] = o.address.index;
    out["subindex"] = o.address.subindex;
    const objif::ObjectInfo& info = *o.info;
    out["type"] = std::string(objif::value_type_name(info.type));
    out["access"] = std::string(objif::access_name(info.access));
    out["readable"] = objif::can_read(info.access);
    out["writable"] = objif::can_write(info.access);
    out["min"] = info.min;
    out["max"] = info.max;
    out["unit"] = std::string(info.unit);
    out["rule"] = std::string(info.rule);
    out["title"] = std::string(info.name);
    return out;
}

std::optional<py::dict> find_by_name(const std::string& name) {
    const objif::NamedObject* o = objif::find_object(std::string_view(name));
    return o != nullptr ? std::optional<py::dict>(object_dict(*o)) : std::nullopt;
}

std::optional<py::dict> find_by_address(std::int32_t bus, std::int32_t device, std::int32_t index,
                                        std::int32_t subindex) {
    const objif::NamedObject* o = objif::find_object(objif::Address{bus, device, index, subindex});
    return o != nullptr ? std::optional<py::dict>(object_dict(*o)) : std::nullopt;
}

std::vector<std::string> nearest(const std::string& name, std::size_t max) {
    std::vector<std::string> out;
    for (std::string_view n : objif::nearest_names(name, max)) out.emplace_back(n);
    return out;
}

std::vector<std::string> closest(const std::string& name, std::size_t max) {
    std::vector<std::string> out;
    for (std::string_view n : objif::closest_names(name, max)) out.emplace_back(n);
    return out;
}

std::vector<std::string> object_names() {
    std::vector<std::string> out;
    for (const objif::NamedObject& o : objif::named_objects()) out.push_back(o.name);
    return out;
}

// ---- Runs

// Collects what the executor reports: the executed and programmed segments and, if asked, the
// sampled axes, at most `max_samples` of them (the first ones; the rest are counted).
class Collector final : public apci::run::RunSink {
  public:
    Collector(bool samples, std::uint64_t max_samples)
        : samples_(samples), max_samples_(max_samples) {}

    void programmed(const apci::run::PathSegment& s) override { program.push_back(s); }
    // The whole contour, also after an error stopped the run (a plot shows where it stopped).
    bool wants_programmed() const override { return true; }
    void executed(const apci::run::PathSegment& s) override { segments.push_back(s); }
    bool wants_samples() const override { return samples_; }
    void axes(std::span<const std::string> names) override {
        axis_names.assign(names.begin(), names.end());
    }
    void sample(std::uint64_t cycle, double time_s, std::span<const double> axes) override {
        if (cycles.size() >= max_samples_) {
            ++samples_dropped;
            return;
        }
        cycles.push_back(cycle);
        times.push_back(time_s);
        for (std::size_t i = 0; i < APCI_AXIS_COUNT; ++i)
            positions.push_back(i < axes.size() ? axes[i]
                                                : std::numeric_limits<double>::quiet_NaN());
    }

    std::vector<apci::run::PathSegment> segments;
    std::vector<apci::run::PathSegment> program;
    std::vector<std::string> axis_names;
    std::vector<std::uint64_t> cycles;
    std::vector<double> times;
    std::vector<double> positions;  // APCI_AXIS_COUNT per sample
    std::uint64_t samples_dropped = 0;

  private:
    bool samples_;
    std::uint64_t max_samples_;
};

py::dict diagnostic_dict(const apci::nc::Diagnostic& d) {
    py::dict out;
    out["kind"] = std::string(apci::nc::error_kind_name(d.kind));
    out["file"] = d.file;
    out["line"] = d.line;
    out["column"] = d.column;
    out["block"] = d.block;
    out["message"] = d.message;
    out["text"] = d.to_string();
    return out;
}

py::dict failure(const apci::nc::Diagnostic& d) {
    py::dict out;
    out["diagnostic"] = diagnostic_dict(d);
    return out;
}

py::list error_list(const std::vector<apci::run::RunError>& errors) {
    py::list out;
    for (const auto& e : errors) {
        py::dict d;
        d["block"] = e.block.number;
        d["line"] = e.block.line;
        d["code"] = e.code;
        d["message"] = e.message;
        d["where"] = apci::run::block_text(e.block);
        out.append(std::move(d));
    }
    return out;
}

// A (n, 3) array of one point field of every segment.
template <class Field>
py::array_t<double> points(const std::vector<apci::run::PathSegment>& segments, Field field) {
    py::array_t<double> out({static_cast<py::ssize_t>(segments.size()), py::ssize_t{3}});
    auto view = out.mutable_unchecked<2>();
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const apci::run::Point& p = field(segments[i]);
        for (py::ssize_t k = 0; k < 3; ++k)
            view(static_cast<py::ssize_t>(i), k) = p[static_cast<Eigen::Index>(k)];
    }
    return out;
}

// One column of every segment.
template <class T, class Field>
py::array_t<T> column(const std::vector<apci::run::PathSegment>& segments, Field field) {
    py::array_t<T> out(static_cast<py::ssize_t>(segments.size()));
    auto view = out.template mutable_unchecked<1>();
    for (std::size_t i = 0; i < segments.size(); ++i)
        view(static_cast<py::ssize_t>(i)) = static_cast<T>(field(segments[i]));
    return out;
}

py::dict segment_columns(const std::vector<apci::run::PathSegment>& s) {
    using apci::run::PathSegment;
    py::dict out;
    out["block"] = column<std::int64_t>(s, [](const PathSegment& x) { return x.block.number; });
    out["line"] = column<std::uint64_t>(s, [](const PathSegment& x) { return x.block.line; });
    out["kind"] = column<std::uint8_t>(s, [](const PathSegment& x) { return x.kind; });
    out["role"] = column<std::uint8_t>(s, [](const PathSegment& x) { return x.role; });
    out["start"] =
        points(s, [](const PathSegment& x) -> const apci::run::Point& { return x.start; });
    out["end"] = points(s, [](const PathSegment& x) -> const apci::run::Point& { return x.end; });
    out["center"] =
        points(s, [](const PathSegment& x) -> const apci::run::Point& { return x.center; });
    out["ccw"] = column<bool>(s, [](const PathSegment& x) { return x.ccw; });
    out["plane"] = column<std::int32_t>(s, [](const PathSegment& x) { return x.plane; });
    out["start_cycle"] =
        column<std::uint64_t>(s, [](const PathSegment& x) { return x.start_cycle; });
    out["end_cycle"] = column<std::uint64_t>(s, [](const PathSegment& x) { return x.end_cycle; });
    return out;
}

py::dict sample_arrays(const Collector& c) {
    py::dict out;
    const auto n = static_cast<py::ssize_t>(c.cycles.size());
    py::array_t<std::uint64_t> cycles(n);
    py::array_t<double> times(n);
    py::array_t<double> axes({n, py::ssize_t{APCI_AXIS_COUNT}});
    std::copy(c.cycles.begin(), c.cycles.end(), cycles.mutable_data());
    std::copy(c.times.begin(), c.times.end(), times.mutable_data());
    std::copy(c.positions.begin(), c.positions.end(), axes.mutable_data());
    out["cycle"] = std::move(cycles);
    out["time"] = std::move(times);
    out["axes"] = std::move(axes);
    return out;
}

// The summary `apcictl run` prints (summary.h) with its warning and notice lines, as text.
std::string summary_text(const apci::run::RunOutcome& result) {
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* out = open_memstream(&buffer, &size);
    if (out == nullptr) return {};
    apci::run::print_summary(out, result.totals, result.errors);
    for (const auto& w : result.warnings)
        fmt::print(out, "warning: {}: {}: {}\n", apci::run::block_text(w.block), w.code, w.message);
    for (const auto& n : result.notices)
        fmt::print(out, "notice: {}: {}\n", apci::run::block_text(n.block), n.message);
    std::fclose(out);
    std::string text(buffer != nullptr ? buffer : "", size);
    std::free(buffer);  // open_memstream's buffer
    return text;
}

// Runs an NC program on `board` as `apcictl run` does (tools/apcictl/command_run.cpp): tool
// list, correction table and PLC script first, then the validation pass (nothing runs from a
// program that does not parse), then the executor. `program` is the text (program_is_text) or
// a path; `tools` likewise. A file or program that cannot be used: {"diagnostic": {...}};
// otherwise the segments, samples, totals, errors, warnings, notices, registers and variables.
py::dict run_program(PyBoard& py_board, const std::string& program, bool program_is_text,
                     const std::string& name, const std::optional<std::string>& tools_source,
                     bool tools_is_text, const std::optional<std::string>& corr_path,
                     const std::optional<std::string>& plc_path, const std::string& self_approach,
                     bool samples, std::uint64_t max_samples) {
    apci::run::RunInputFiles files;
    files.tools = tools_source;
    files.tools_is_text = tools_is_text;
    files.corrections = corr_path;
    files.plc = plc_path;
    files.tools_name = "tools";
    files.corrections_name = "corr";
    auto inputs = apci::run::load_run_inputs(files);
    if (!inputs) return failure(inputs.error());

    const PyBoard::Use use(py_board);
    // The board's motion is the run's while it runs, as for `apcictl run` (docs/motion-claim.md),
    // unless the caller's handle holds it already. Held by another program:
    // {"claimed": libapci's words naming the holder, "status": the code}; refused otherwise (a
    // lost link): {"board_error": the words, "status": the code}. Nothing ran either way.
    apci::Board& board = py_board.board(use);
    std::optional<apci::MotionClaim> claim;
    if (const auto held = board.motion_claim(); !(held.ok() && held.value.yours != 0)) {
        claim.emplace(board);
        if (!claim->held() && claim->status() != APCI_NOT_SUPPORTED) {
            py::dict out;
            if (claim->status() == APCI_MOTION_CLAIMED)
                out["claimed"] = std::string(board.last_error());
            else  // a lost link: the board's words
                out["board_error"] = "claim the board's motion: " +
                                     apci::run::board_words(board, kLostLinkHint);
            out["status"] = claim->status();
            return out;
        }
    }
    Collector collector(samples, max_samples);
    apci::run::RunSettings settings;
    const auto mode = apci::run::self_approach_mode(self_approach);
    if (!mode)
        throw py::value_error("self_approach must be warn, error or off, not " + self_approach);
    settings.self_approach = *mode;
    settings.dry_run_first = !apci::run::embedded_emulator(py_board.uri());
    settings.lost_link_hint = std::string(kLostLinkHint);
    const apci::run::ProgramSource source = program_is_text
                                                ? apci::run::ProgramSource::in_memory(program, name)
                                                : apci::run::ProgramSource::file(program);
    std::optional<apci::nc::Result<apci::run::RunOutcome>> ran;
    {
        py::gil_scoped_release unlocked;
        ran.emplace(apci::run::run_program(board, collector, inputs.value(), source, settings));
    }
    if (!*ran) return failure(ran->error());
    const apci::run::RunOutcome& result = ran->value();

    py::dict out;
    out["file"] = result.totals.file;
    out["blocks"] = result.totals.blocks;
    out["blocks_executed"] = result.totals.blocks_executed;
    out["segment_count"] = result.totals.segments;
    out["path_length"] = result.totals.path_length;
    out["rapid_length"] = result.totals.rapid_length;
    out["cycles"] = result.totals.cycles;
    out["cycle_seconds"] = result.totals.cycle_seconds;
    out["segments"] = segment_columns(collector.segments);
    out["programmed"] = segment_columns(collector.program);
    out["samples"] = sample_arrays(collector);
    out["samples_dropped"] = collector.samples_dropped;
    out["axis_names"] =
        collector.axis_names.empty()
            ? std::vector<std::string>(result.axis_names.begin(), result.axis_names.end())
            : collector.axis_names;
    out["axis_numbers"] = std::vector<int>(result.axis_numbers.begin(), result.axis_numbers.end());
    out["plot_plane"] = result.plot_plane;
    out["tc_present"] = result.tc_present;
    out["errors"] = error_list(result.errors);
    out["warnings"] = error_list(result.warnings);
    out["notices"] = error_list(result.notices);
    py::list registers;
    for (const auto& r : result.registers) {
        py::dict d;
        d["group"] = r.group;
        d["readable"] = r.readable;
        d["error"] = r.error;
        d["status"] = r.status;
        registers.append(std::move(d));
    }
    out["registers"] = std::move(registers);
    out["variables"] = result.variables;
    out["summary"] = summary_text(result);
    return out;
}

}  // namespace

PYBIND11_MODULE(_apci, m) {
    m.doc() = "libapci for Python: boards, objects, NC runs (the package apci wraps this module)";
    m.attr("AXIS_COUNT") = APCI_AXIS_COUNT;
    m.attr("TC_BUS") = APCI_TC_BUS;
    m.def(
        "version", [] { return std::string(apci_version()); },
        "The version of the libapci loaded.");
    m.def("status_name", [](apci::Status s) { return std::string(apci_status_name(s)); });
    m.def("status_message", [](apci::Status s) { return std::string(apci_status_message(s)); });
    m.def("status_codes", &status_codes, "(name, code) of every status code apci.h lists.");
    m.def(
        "last_open_error", [] { return std::string(apci_last_error(nullptr)); },
        "apci_last_error(NULL): why the last open on this thread failed.");
    m.def(
        "tc_error_bits", [] { return tc_bits(&apci_tc_error_bit_name); },
        "(name, mask) of every TC ERROR bit of [APCI-TC] Table 4.");
    m.def(
        "tc_status_bits", [] { return tc_bits(&apci_tc_status_bit_name); },
        "(name, mask) of every TC STATUS bit of [APCI-TC] Table 5.");
    m.def("segment_role_name", [](int role) -> std::optional<std::string> {
        const char* n = apci_segment_role_name(role);
        return n != nullptr ? std::optional<std::string>(n) : std::nullopt;
    });
    m.def(
        "run_kind_names",
        [] {
            using apci::run::SegmentKind;
            std::vector<std::string> out;
            for (auto k : {SegmentKind::kRapid, SegmentKind::kLine, SegmentKind::kArc})
                out.emplace_back(apci::run::kind_name(k));
            return out;
        },
        "The JSON names of the run's segment kinds, by their numbers.");
    m.def(
        "run_role_names",
        [] {
            using apci::run::Role;
            std::vector<std::string> out;
            for (auto r : {Role::kContour, Role::kTransition, Role::kApproach, Role::kDeparture,
                           Role::kUncompensated})
                out.emplace_back(apci::run::role_name(r));
            return out;
        },
        "The JSON names of the run's segment roles, by their numbers.");

    m.def("find_object", &find_by_name, py::arg("name"),
          "The map's object of a dotted name (objif/names.h) as a dict, or None.");
    m.def("find_object_at", &find_by_address, py::arg("bus"), py::arg("device"), py::arg("index"),
          py::arg("subindex"),
          "The map's object at an address as a dict, or None when the map has none there.");
    m.def("nearest_names", &nearest, py::arg("name"), py::arg("max") = 3,
          "Up to `max` names close to `name`, nearest first.");
    m.def("closest_names", &closest, py::arg("name"), py::arg("max") = 3,
          "Of nearest_names, only those as close as the closest (what an error suggests).");
    m.def("object_names", &object_names, "Every dotted name of the map, in map order.");

    py::class_<PyBoard>(m, "Board")
        .def(py::init<const std::string&>(), py::arg("uri"))
        .def_property_readonly("is_open", &PyBoard::is_open)
        .def_property_readonly("open_status", &PyBoard::open_status)
        .def_property_readonly("uri", &PyBoard::uri)
        .def("last_error", &PyBoard::last_error)
        .def("close", &PyBoard::close)
        .def("read_int", &PyBoard::read_int)
        .def("read_double", &PyBoard::read_double)
        .def("write_int", &PyBoard::write_int)
        .def("write_double", &PyBoard::write_double)
        .def("claim_motion", &PyBoard::claim_motion)
        .def("release_motion", &PyBoard::release_motion)
        .def("motion_claim", &PyBoard::motion_claim);

    m.def("run_program", &run_program, py::arg("board"), py::arg("program"),
          py::arg("program_is_text"), py::arg("name"), py::arg("tools"), py::arg("tools_is_text"),
          py::arg("corr"), py::arg("plc"), py::arg("self_approach"), py::arg("samples"),
          py::arg("max_samples"), "Runs an NC program on an open board as `apcictl run` does.");
}
