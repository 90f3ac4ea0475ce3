// SPDX-License-Identifier: MIT
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "apci/nc/correction_table.h"
#include "apci/nc/klartext.h"
#include "apci/nc/tools.h"
#include "block_context.h"

namespace apci::nc {

namespace {

// A summed delta above this is an oversize (the board's kOversizeTolerance).
constexpr double kOversizeTolerance = 1e-9;
// R2 may exceed R by this much (the board's kShapeTolerance).
constexpr double kShapeTolerance = 1e-9;

constexpr char kAxisLetter[3] = {'X', 'Y', 'Z'};

using BlockCheck = BlockContext<KlartextBlock>;

std::uint32_t m_column(const KlartextBlock& b, int code) {
    for (std::size_t i = 0; i < b.m_count; ++i) {
        if (b.m[i].value == code) return b.m[i].column;
    }
    return 0;
}

// The summed deltas of the tool list and the tool call, and the tool they leave.
struct CalledTool {
    double r = 0.0, r2 = 0.0;
    double dl = 0.0, dr = 0.0, dr2 = 0.0;
};

bool has_oversize(const CalledTool& t) {
    return t.dl > kOversizeTolerance || t.dr > kOversizeTolerance || t.dr2 > kOversizeTolerance;
}

// The correction table row's deltas: 0 for row 0, and when no table is given.
CorrectionRow correction_deltas(const CorrectionTable* table, int row) {
    const CorrectionRow* r = table != nullptr && row > 0 ? table->find(row) : nullptr;
    return r != nullptr ? *r : CorrectionRow{};
}

// The checks on the tool the deltas leave (the board's check_tool_load): `subject` names the
// block ("TOOL CALL 3", "FUNCTION CORRDATA TCS #2 (tool 3)"), `known`: R and R2 are known.
bool check_called(const BlockCheck& c, std::string_view subject, std::string_view before_what,
                  bool known, const CalledTool& called, bool m107, std::uint32_t column) {
    const double r = called.r + called.dr;
    const double r2 = called.r2 + called.dr2;
    if (known && (r < -kShapeTolerance || r2 < -kShapeTolerance)) {
        return c.fail(ErrorKind::kProgramRule, column,
                      fmt::format("{}: R + DR = {:.4f} mm, R2 + DR2 = {:.4f} mm: the deltas take "
                                  "away more than the tool has",
                                  subject, r, r2));
    }
    if (known && r2 > r + kShapeTolerance) {
        return c.fail(ErrorKind::kProgramRule, column,
                      fmt::format("{}: R2 + DR2 = {:.4f} mm is larger than R + DR = {:.4f} mm: "
                                  "no such tool",
                                  subject, r2, r));
    }
    // [TNC-3D]: calling a tool with positive delta values is an error unless M107 allows it.
    if (has_oversize(called) && !m107) {
        return c.fail(ErrorKind::kProgramRule, column,
                      fmt::format("{} with a positive oversize (summed DL {:+.4f}, DR {:+.4f}, DR2 "
                                  "{:+.4f} mm): program M107 before {} to allow it",
                                  subject, called.dl, called.dr, called.dr2, before_what));
    }
    return true;
}

// Tool n of the list with the given call deltas and correction row; false when the list does
// not define a valid tool n or its R2 exceeds R.
bool called_tool(const BlockCheck& c, const ToolTable* tools, int n, std::uint32_t column,
                 double call_dl, double call_dr, double call_dr2, const CorrectionRow& corr,
                 CalledTool& called) {
    called.dl = call_dl + corr.dl;
    called.dr = call_dr + corr.dr;
    called.dr2 = call_dr2 + corr.dr2;
    if (tools == nullptr || n <= 0) return true;
    const ToolData* t = tools->find(n);
    if (t == nullptr) {
        c.fail(ErrorKind::kProgramRule, column,
               fmt::format("TOOL CALL {}: the tool list does not define tool {}", n, n));
        c.err.undefined = Undefined::kTool;
        return false;
    }
    if (!t->valid()) {
        return c.fail(ErrorKind::kProgramRule, column,
                      fmt::format("TOOL CALL {}: tool {} is not valid (wz[{}].gueltig is {}, not "
                                  "1; unset data is 0)",
                                  n, n, n, t->gueltig));
    }
    called.r = t->radius_mm();
    called.r2 = t->r2_mm();
    called.dl += t->dl_mm();
    called.dr += t->dr_mm();
    called.dr2 += t->dr2_mm();
    if (called.r2 > called.r + kShapeTolerance) {
        return c.fail(ErrorKind::kProgramRule, column,
                      fmt::format("TOOL CALL {}: corner radius R2 {:.4f} mm is larger than the "
                                  "radius R {:.4f} mm in the tool list",
                                  n, called.r2, called.r));
    }
    return true;
}

bool check_tool_call(const BlockCheck& c, const KlartextState& before,
                     const KlartextOptions& options, CalledTool& called) {
    const KlartextBlock& b = c.b;
    const int n = b.tool.value;
    // As D in DIN 66025: the TC module takes a tool index only while compensation is off
    // ([APCI-TC], Table 3: WKZINDEX).
    if (before.radius_comp != Compensation::kOff) {
        return c.fail(ErrorKind::kProgramRule, b.kind_column,
                      fmt::format("TOOL CALL {} while radius compensation {} is on: program R0 "
                                  "in an earlier block",
                                  n, before.radius_comp == Compensation::kLeft ? "RL" : "RR"));
    }
    if (b.tool_axis.present() && b.tool_axis.value != 'Z') {
        return c.fail(ErrorKind::kUnsupported, b.tool_axis.column,
                      fmt::format("tool axis {}: only Z is supported (the documented head tilts "
                                  "the Z tool axis)",
                                  b.tool_axis.value));
    }
    if (!called_tool(c, options.tools, n, b.tool.column, b.dl.present() ? b.dl.value : 0.0,
                     b.dr.present() ? b.dr.value : 0.0, b.dr2.present() ? b.dr2.value : 0.0,
                     correction_deltas(options.corrections, before.corr_row), called))
        return false;
    // Without a tool list R and R2 are unknown: only the oversize rule can be checked here.
    if (n <= 0) return true;
    return check_called(c, fmt::format("TOOL CALL {}", n), "the TOOL CALL",
                        options.tools != nullptr, called, before.m107, b.kind_column);
}

// FUNCTION CORRDATA: the row must be in the table (when one is given); the tool in force with
// the new row's deltas passes the tool checks, as the board's CorrectionRow write does.
bool check_corrdata(const BlockCheck& c, const KlartextState& before,
                    const KlartextOptions& options, CalledTool& called) {
    const KlartextBlock& b = c.b;
    const int row = b.corr_row.value;
    if (options.corrections != nullptr && row > 0 && options.corrections->find(row) == nullptr) {
        c.fail(ErrorKind::kProgramRule, b.corr_row.column,
               fmt::format("FUNCTION CORRDATA TCS #{}: the correction table does not define row {}",
                           row, row));
        c.err.undefined = Undefined::kCorrectionRow;
        return false;
    }
    if (before.tool <= 0) return true;
    if (!called_tool(c, options.tools, before.tool, b.kind_column, before.call_dl, before.call_dr,
                     before.call_dr2, correction_deltas(options.corrections, row), called))
        return false;
    const std::string subject =
        row > 0 ? fmt::format("FUNCTION CORRDATA TCS #{} (tool {})", row, before.tool)
                : fmt::format("FUNCTION CORRDATA RESET TCS (tool {})", before.tool);
    return check_called(c, subject, "FUNCTION CORRDATA", options.tools != nullptr, called,
                        before.m107, b.kind_column);
}

struct VectorCheck {
    bool present = false;
    Eigen::Vector3d unit = Eigen::Vector3d::Zero();
};

// All three components or none; normalised within kVectorLengthTolerance.
bool check_vector(const BlockCheck& c, const std::array<Word<double>, 3>& w, char prefix,
                  std::string_view name, VectorCheck& out) {
    int count = 0;
    for (const auto& x : w) count += x.present() ? 1 : 0;
    if (count == 0) return true;
    if (count < 3) {
        std::string missing;
        for (std::size_t k = 0; k < 3; ++k) {
            if (w[k].present()) continue;
            if (!missing.empty()) missing += ' ';
            missing += fmt::format("{}{}", prefix, kAxisLetter[k]);
        }
        return c.fail(
            ErrorKind::kSyntax, c.b.kind_column,
            fmt::format("LN needs all three components of {} {}X {}Y {}Z: {} {} missing", name,
                        prefix, prefix, prefix, missing, missing.size() > 2 ? "are" : "is"));
    }
    const Eigen::Vector3d v(w[0].value, w[1].value, w[2].value);
    const double length = v.norm();
    if (!(std::abs(length - 1.0) <= kVectorLengthTolerance)) {
        return c.fail(ErrorKind::kValue, w[0].column,
                      fmt::format("{} ({}X {}Y {}Z) is not normalised: its length is {:.7f}, not 1 "
                                  "(tolerance {})",
                                  name, prefix, prefix, prefix, length, kVectorLengthTolerance));
    }
    out.present = true;
    out.unit = v / length;
    return true;
}

bool vector_line(const BlockCheck& c, const KlartextState& s, const Eigen::Vector3d& start,
                 VectorLineMove& out) {
    const KlartextBlock& b = c.b;
    std::string missing;
    for (std::size_t k = 0; k < 3; ++k) {
        if (b.axis[k].present()) continue;
        if (!missing.empty()) missing += ' ';
        missing += kAxisLetter[k];
    }
    // [TNC-3D], "Gerade LN", Hinweise: every LN block holds all coordinates, even unchanged.
    if (!missing.empty()) {
        return c.fail(ErrorKind::kSyntax, b.kind_column,
                      fmt::format("LN needs all coordinates X Y Z, even when unchanged: {} {} "
                                  "missing",
                                  missing, missing.size() > 1 ? "are" : "is"));
    }
    VectorCheck n;
    VectorCheck t;
    if (!check_vector(c, b.normal, 'N', "the surface normal N", n)) return false;
    if (!check_vector(c, b.tool_vector, 'T', "the tool vector T", t)) return false;
    // [TNC-3D], peripheral milling: "LN-Satz mit Werkzeugorientierung T ohne N-Vektor, M128 oder
    // FUNCTION TCPM aktiv" is the only LN without N.
    if (!n.present && !(t.present && s.tcpm)) {
        return c.fail(ErrorKind::kSyntax, b.kind_column,
                      t.present ? "LN without NX NY NZ needs M128 or FUNCTION TCPM (peripheral "
                                  "milling with the tool vector T)"
                                : "LN needs the surface normal NX NY NZ (only peripheral milling "
                                  "with TX TY TZ under M128 or FUNCTION TCPM may leave it out)");
    }
    if (n.present && t.present && s.tcpm && n.unit.dot(t.unit) < -kNormalAgainstToolTolerance) {
        return c.fail(ErrorKind::kGeometry, b.normal[0].column,
                      fmt::format("the surface normal N points against the tool vector T (N.T = "
                                  "{:.4f}): the tool cannot touch the surface from this side",
                                  n.unit.dot(t.unit)));
    }
    out.start = start;
    out.end = Eigen::Vector3d(b.axis[0].value, b.axis[1].value, b.axis[2].value);
    out.has_normal = n.present;
    out.normal = n.unit;
    out.tool_vector_programmed = t.present;
    // [TNC-3D], face milling: with TCPM the programmed T, or N; without TCPM T is ignored.
    out.has_tool_vector = s.tcpm;
    out.tool_vector = !s.tcpm ? Eigen::Vector3d::Zero() : t.present ? t.unit : n.unit;
    out.side = s.radius_comp;
    out.rapid = b.fmax.present();
    out.feed = out.rapid ? 0.0 : s.feed;
    return true;
}

Eigen::Vector3d line_end(const KlartextBlock& b, const Eigen::Vector3d& from) {
    Eigen::Vector3d end = from;
    for (std::size_t k = 0; k < 3; ++k) {
        if (!b.axis[k].present()) continue;
        const auto i = static_cast<int>(k);
        end[i] = b.axis_incremental[k] ? from[i] + b.axis[k].value : b.axis[k].value;
    }
    return end;
}

std::uint32_t first_axis_column(const KlartextBlock& b) {
    std::uint32_t col = 0;
    for (const auto& w : b.axis) {
        if (w.present() && (col == 0 || w.column < col)) col = w.column;
    }
    return col == 0 ? b.kind_column : col;
}

}  // namespace

namespace {

// The column of the block's feed word, else of its first axis word.
std::uint32_t feed_column(const KlartextBlock& b) noexcept {
    for (const auto* w : {&b.feed, &b.feed_per_tooth, &b.feed_per_rev})
        if (w->present()) return w->column;
    if (b.feed_auto.present()) return b.feed_auto.column;
    return first_axis_column(b);
}

// [TNC-3D], "Gerade LN": "F, FMAX, FZ, FU oder F AUTO". FZ is per tooth: F = FZ x the tool's
// teeth (the TNC tool table's CUT, the tool list's wz[n].cut) x S; FU per revolution: F = FU x
// S; F AUTO the F of the TOOL CALL. S is the spindle speed the TOOL CALLs gave. Sets s.feed (mm/
// min) for the move; what is missing is named.
bool feed_of_move(const BlockCheck& c, const KlartextBlock& b, const KlartextOptions& options,
                  KlartextState& s) {
    const std::uint32_t col = feed_column(b);
    const auto need_speed = [&](std::string_view what) {
        return c.fail(ErrorKind::kProgramRule, col,
                      fmt::format("{} needs the spindle speed: give S in the TOOL CALL (TOOL CALL "
                                  "{} Z S..)",
                                  what, s.tool));
    };
    switch (s.feed_mode) {
        case KlartextFeed::kPerMinute:
            return true;
        case KlartextFeed::kPerRevolution:
            if (!(s.spindle_speed > 0.0)) return need_speed(fmt::format("FU{}", s.feed_per_rev));
            s.feed = s.feed_per_rev * s.spindle_speed;
            return true;
        case KlartextFeed::kPerTooth: {
            const std::string what = fmt::format("FZ{}", s.feed_per_tooth);
            if (!(s.spindle_speed > 0.0)) return need_speed(what);
            const ToolData* t =
                options.tools != nullptr && s.tool > 0 ? options.tools->find(s.tool) : nullptr;
            if (s.tool == 0)
                return c.fail(ErrorKind::kProgramRule, col,
                              fmt::format("{} needs the number of teeth of the tool in force, and "
                                          "no tool is called: program TOOL CALL first",
                                          what));
            if (t == nullptr || t->cut <= 0)
                return c.fail(
                    ErrorKind::kProgramRule, col,
                    fmt::format("{} needs the number of teeth of tool {}: {} (wz[{}].cut, the TNC "
                                "tool table's CUT)",
                                what, s.tool,
                                options.tools == nullptr ? "no tool list was given"
                                                          : "the tool list does not give it",
                                s.tool));
            s.feed = s.feed_per_tooth * t->cut * s.spindle_speed;
            return true;
        }
        case KlartextFeed::kAuto:
            if (!(s.call_feed > 0.0))
                return c.fail(ErrorKind::kProgramRule, col,
                              fmt::format("F AUTO takes the feed of the TOOL CALL, and TOOL CALL "
                                          "{} gives none: program F in the TOOL CALL",
                                          s.tool));
            s.feed = s.call_feed;
            return true;
    }
    return true;
}

// A block where the program's frame allows it: after BEGIN PGM (which comes first), before END
// PGM, and after M2/M30 only END PGM.
bool check_block_order(const BlockCheck& c, const KlartextState& before) {
    const KlartextBlock& b = c.b;
    if (before.closed) {
        return c.fail(ErrorKind::kProgramRule, b.kind_column,
                      "block after END PGM: the program has already ended");
    }
    if (!before.begun && b.kind != KlartextKind::kBeginPgm) {
        return c.fail(ErrorKind::kProgramRule, b.kind_column,
                      "a Klartext program begins with 'BEGIN PGM name MM'");
    }
    if (before.ended && b.kind != KlartextKind::kEndPgm) {
        return c.fail(ErrorKind::kProgramRule, b.kind_column,
                      "block after M2/M30: only END PGM may follow");
    }
    return true;
}

// BEGIN PGM name MM: once per file, in mm.
bool begin_program(const BlockCheck& c, const KlartextState& before, KlartextState& s) {
    const KlartextBlock& b = c.b;
    if (before.begun) {
        return c.fail(ErrorKind::kProgramRule, b.kind_column,
                      "BEGIN PGM appears twice: one program per file");
    }
    if (b.inch.value) {
        return c.fail(ErrorKind::kUnsupported, b.inch.column,
                      "INCH programs are not supported: the emulator works in mm (write "
                      "the program in MM)");
    }
    s.begun = true;
    s.inch = b.inch.value;
    return true;
}

// END PGM with the name and unit of BEGIN PGM; the program ends here unless M2/M30 ended it.
bool end_program(const BlockCheck& c, const KlartextState& before, std::string_view program_name,
                 const BlockOrigin& origin, KlartextState& s, EventBatch& out) {
    const KlartextBlock& b = c.b;
    if (b.program_name != program_name) {
        return c.fail(ErrorKind::kProgramRule, b.program_name_column,
                      fmt::format("END PGM {} does not match BEGIN PGM {}", b.program_name,
                                  program_name));
    }
    if (b.inch.value != before.inch) {
        return c.fail(ErrorKind::kProgramRule, b.inch.column,
                      "END PGM gives another unit than BEGIN PGM");
    }
    if (!before.ended) out.push(origin, ProgramEnd{});
    s.closed = true;
    return true;
}

// TOOL CALL n Z S.. F.. DL.. DR.. DR2..: the tool, its spindle speed, feed and deltas.
bool tool_call(const BlockCheck& c, const KlartextState& before, const KlartextOptions& options,
               const BlockOrigin& origin, KlartextState& s, EventBatch& out) {
    const KlartextBlock& b = c.b;
    CalledTool called;
    if (!check_tool_call(c, before, options, called)) return false;
    s.tool = b.tool.value;
    // S stays in force until a TOOL CALL gives another; F belongs to its call (F AUTO).
    if (b.spindle_speed.present()) s.spindle_speed = b.spindle_speed.value;
    s.call_feed = b.call_feed.present() ? b.call_feed.value : 0.0;
    s.call_dl = b.dl.present() ? b.dl.value : 0.0;
    s.call_dr = b.dr.present() ? b.dr.value : 0.0;
    s.call_dr2 = b.dr2.present() ? b.dr2.value : 0.0;
    s.tool_oversize = s.tool > 0 && has_oversize(called);
    out.push(origin, ToolSelect{s.tool});
    out.push(origin, ToolCallDeltas{s.tool, s.call_dl, s.call_dr, s.call_dr2,
                                    b.spindle_speed.present() ? b.spindle_speed.value : 0.0});
    return true;
}

// FUNCTION CORRDATA TCS #n: the correction table's row for the tool in force.
bool correction_data(const BlockCheck& c, const KlartextState& before,
                     const KlartextOptions& options, const BlockOrigin& origin, KlartextState& s,
                     EventBatch& out) {
    CalledTool called;
    if (!check_corrdata(c, before, options, called)) return false;
    s.corr_row = c.b.corr_row.value;
    s.tool_oversize = s.tool > 0 && has_oversize(called);
    out.push(origin, CorrectionSelect{s.corr_row});
    return true;
}

// FUNCTION PROG PATH IS CONTOUR / IS CENTER.
void prog_path(const KlartextBlock& b, const KlartextState& before, const BlockOrigin& origin,
               KlartextState& s, EventBatch& out) {
    s.prog_path_contour = b.prog_path_contour;
    if (s.prog_path_contour != before.prog_path_contour) {
        out.push(origin, ProgPathChange{s.prog_path_contour});
    }
}

// FUNCTION TCPM and FUNCTION RESET TCPM.
void tcpm_function(const KlartextBlock& b, const KlartextState& before,
                   const BlockOrigin& origin, KlartextState& s, EventBatch& out) {
    s.tcpm = b.kind == KlartextKind::kTcpm;
    s.reference = s.tcpm ? b.reference : ToolReference::kTip;
    if (s.tcpm != before.tcpm || s.reference != before.reference) {
        out.push(origin, TcpmChange{s.tcpm, s.reference});
    }
}

// The M functions of an L, LN or M block (they act at the start of the block) and its modal
// words: radius compensation, feed, head angles.
bool modal_words(const BlockCheck& c, const KlartextState& before, KlartextState& s) {
    const KlartextBlock& b = c.b;
    if (b.has_m(107)) s.m107 = true;
    if (b.has_m(108)) {
        if (before.tool_oversize) {
            return c.fail(ErrorKind::kProgramRule, m_column(b, 108),
                          fmt::format("M108 while tool {} with a positive oversize is loaded: "
                                      "call a tool without oversize first",
                                      before.tool));
        }
        s.m107 = false;
    }
    if (b.has_m(128)) {
        s.tcpm = true;
        s.reference = ToolReference::kTip;
    }
    if (b.has_m(129)) {
        s.tcpm = false;
        s.reference = ToolReference::kTip;
    }
    if (b.radius_comp.present()) s.radius_comp = b.radius_comp.value;
    if (b.feed.present()) {
        s.feed_mode = KlartextFeed::kPerMinute;
        s.feed = b.feed.value;
    } else if (b.feed_per_tooth.present()) {
        s.feed_mode = KlartextFeed::kPerTooth;
        s.feed_per_tooth = b.feed_per_tooth.value;
    } else if (b.feed_per_rev.present()) {
        s.feed_mode = KlartextFeed::kPerRevolution;
        s.feed_per_rev = b.feed_per_rev.value;
    } else if (b.feed_auto.present()) {
        s.feed_mode = KlartextFeed::kAuto;
    }
    if (b.b.present()) s.b = b.b.value;
    if (b.c.present()) s.c = b.c.value;
    return true;
}

// The move of an L or LN block (none for an M block or an L without axis words) into `move`,
// `s.position` its end; its feed in mm/min (FZ, FU, F AUTO turned into it here), and the
// number of interpolation cycles it takes, checked.
bool block_move(const BlockCheck& c, const KlartextState& before, const KlartextOptions& options,
                KlartextState& s, std::optional<EventData>& move) {
    const KlartextBlock& b = c.b;
    const bool will_move =
        b.kind == KlartextKind::kVectorLine || (b.kind == KlartextKind::kLine && b.has_axis_word());
    if (!will_move) return true;
    if (!b.fmax.present() && !feed_of_move(c, b, options, s)) return false;
    if (b.kind == KlartextKind::kVectorLine) {
        VectorLineMove ln;
        if (!vector_line(c, s, before.position, ln)) return false;
        move = ln;
        s.position = ln.end;
    } else {
        const Eigen::Vector3d end = line_end(b, before.position);
        if (b.fmax.present()) {
            move = RapidMove{before.position, end};
        } else {
            move = LineMove{before.position, end, s.feed};
        }
        s.position = end;
    }
    if (b.fmax.present()) return true;
    if (!(s.feed > 0.0)) {
        return c.fail(ErrorKind::kProgramRule, first_axis_column(b),
                      fmt::format("no feed rate: program F (or FMAX) before the first {} move",
                                  b.kind == KlartextKind::kVectorLine ? "LN" : "L"));
    }
    std::string why = check_move_cycles(move_length(before.position, s.position), s.feed,
                                        options.cycle_seconds);
    if (!why.empty())
        return c.fail(ErrorKind::kValue, b.feed.present() ? b.feed.column : first_axis_column(b),
                      std::move(why));
    return true;
}

// L, LN and M blocks. M functions act at the start of the block, M2/M30 at its end. Once
// every check has passed, the events in the documented order.
bool move_block(const BlockCheck& c, const KlartextState& before, const KlartextOptions& options,
                const BlockOrigin& origin, KlartextState& s, EventBatch& out) {
    const KlartextBlock& b = c.b;
    if (!modal_words(c, before, s)) return false;
    std::optional<EventData> move;
    if (!block_move(c, before, options, s, move)) return false;
    if (b.has_m(2) || b.has_m(30)) s.ended = true;

    if (s.m107 != before.m107) out.push(origin, OversizeChange{s.m107});
    if (s.tcpm != before.tcpm || s.reference != before.reference) {
        out.push(origin, TcpmChange{s.tcpm, s.reference});
    }
    if (s.radius_comp != before.radius_comp) out.push(origin, CompensationChange{s.radius_comp});
    if (b.b.present() || b.c.present()) out.push(origin, HeadOrientation{s.b, s.c});
    if (move) out.push(origin, *move);
    if (s.ended) out.push(origin, ProgramEnd{});
    return true;
}

}  // namespace

KlartextInterpreter::KlartextInterpreter(const KlartextOptions& options) : options_(options) {
    state_.position = options_.start_position;
}

bool KlartextInterpreter::apply(const KlartextBlock& b, std::string_view file, EventBatch& out,
                                Diagnostic& err) {
    out.clear();
    const BlockCheck c{b, file, err, true};
    if (b.kind == KlartextKind::kEmpty) return true;
    if (!check_block_order(c, state_)) return false;
    KlartextState s = state_;  // committed only when every check has passed
    const BlockOrigin origin{b.block_number(), b.line};
    bool ok = true;
    switch (b.kind) {
        case KlartextKind::kEmpty:
            return true;
        case KlartextKind::kBeginPgm:
            ok = begin_program(c, state_, s);
            if (ok) program_name_.assign(b.program_name);
            break;
        case KlartextKind::kEndPgm:
            ok = end_program(c, state_, program_name_, origin, s, out);
            break;
        case KlartextKind::kToolCall:
            ok = tool_call(c, state_, options_, origin, s, out);
            break;
        case KlartextKind::kCorrData:
            ok = correction_data(c, state_, options_, origin, s, out);
            break;
        case KlartextKind::kProgPath:
            prog_path(b, state_, origin, s, out);
            break;
        case KlartextKind::kTcpm:
        case KlartextKind::kResetTcpm:
            tcpm_function(b, state_, origin, s, out);
            break;
        case KlartextKind::kLine:
        case KlartextKind::kVectorLine:
        case KlartextKind::kMOnly:
            ok = move_block(c, state_, options_, origin, s, out);
            break;
    }
    if (!ok) return false;
    state_ = s;
    return true;
}

}  // namespace apci::nc
