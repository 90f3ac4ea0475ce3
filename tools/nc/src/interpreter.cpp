// SPDX-License-Identifier: MIT
#include "apci/nc/interpreter.h"

#include <fmt/format.h>

#include <cmath>

#include "apci/nc/arc.h"
#include "apci/nc/move_time.h"
#include "apci/nc/tools.h"
#include "block_context.h"

namespace apci::nc {

namespace {

constexpr char kCenterLetter[3] = {'I', 'J', 'K'};
constexpr char kAxisLetter[3] = {'X', 'Y', 'Z'};

bool is_arc(Motion m) {
    return m == Motion::kArcCw || m == Motion::kArcCcw;
}

// The context of one apply() call, so that the rule checks below stay short.
using BlockCheck = BlockContext<Block>;

bool check_tool(const BlockCheck& c, const ModalState& before, const ToolTable* tools) {
    const Word<int>& d = c.b.tool;
    if (!d.present()) return true;
    if (before.trafo && d.value != before.tool) {
        return c.fail(ErrorKind::kProgramRule, d.column,
                      fmt::format("D{} while #TRAFO is on: the transformation holds the tool's "
                                  "length; program #TRAFO OFF before a tool change",
                                  d.value));
    }
    // The OTC module keeps the tool while OTC is on (docs/otc.md, OTC_TOOL_CHANGE_WHILE_ACTIVE).
    if (before.otc_active && d.value != before.tool) {
        return c.fail(ErrorKind::kProgramRule, d.column,
                      fmt::format("OTC_TOOL_CHANGE_WHILE_ACTIVE: D{} while OTC is on: program "
                                  "#OTC OFF before a tool change",
                                  d.value));
    }
    // The TC module takes a tool index only while compensation is inactive ([APCI-TC]
    // Table 3: WKZINDEX), so a tool change needs G40 first.
    if (before.compensation != Compensation::kOff) {
        return c.fail(ErrorKind::kProgramRule, d.column,
                      fmt::format("D{} while radius compensation G{} is on: program G40 in an "
                                  "earlier block before selecting a tool",
                                  d.value, g_number(before.compensation)));
    }
    if (tools == nullptr || d.value == 0) return true;
    const ToolData* t = tools->find(d.value);
    if (t == nullptr) {
        c.fail(ErrorKind::kProgramRule, d.column,
               fmt::format("D{} selects tool {}, which the tool list does not define", d.value,
                           d.value));
        c.err.undefined = Undefined::kTool;
        return false;
    }
    if (!t->valid()) {
        return c.fail(ErrorKind::kProgramRule, d.column,
                      fmt::format("D{} selects tool {}, which is not valid (wz[{}].gueltig is {}, "
                                  "not 1; unset data is 0)",
                                  d.value, d.value, d.value, t->gueltig));
    }
    return true;
}

bool check_plane(const BlockCheck& c, const ModalState& before, Compensation comp_after) {
    const Word<Plane>& p = c.b.plane;
    if (!p.present() || p.value == before.plane) return true;
    if (before.compensation != Compensation::kOff || comp_after != Compensation::kOff) {
        return c.fail(ErrorKind::kProgramRule, p.column,
                      fmt::format("G{} changes the plane while radius compensation is on: "
                                  "program G40 before changing the plane",
                                  g_number(p.value)));
    }
    return true;
}

// A turning tool's cutting edge position (srk_lage 1..8, ISG P-TOOL-00002) is given in the
// turning plane: its radius compensation runs in G18 (Z-X) only, as LinuxCNC's does ("G41 with
// lathe tool, but plane is not G18"); and only a turning tool (typ 1, P-TOOL-00001) has one.
bool check_cutting_edge(const BlockCheck& c, const ModalState& after, const ToolTable* tools) {
    const ToolData* t = tools != nullptr && after.tool > 0 ? tools->find(after.tool) : nullptr;
    if (t == nullptr || t->srk_lage < 1 || t->srk_lage > 8) return true;
    const std::uint32_t col = c.b.compensation.column;
    if (t->type() != ToolType::kTurning) {
        return c.fail(ErrorKind::kProgramRule, col,
                      fmt::format("G{} with D{}: its cutting edge position (srk_lage {}) is a "
                                  "turning tool's, and D{} is type {}: set wz[{}].typ 1 "
                                  "(P-TOOL-00001) or srk_lage 0",
                                  g_number(after.compensation), after.tool, t->srk_lage,
                                  after.tool, t->typ, after.tool));
    }
    if (after.plane != Plane::kZX) {
        return c.fail(ErrorKind::kProgramRule, col,
                      fmt::format("G{} with the turning tool D{} (cutting edge position {}) in "
                                  "G{}: the cutting edge position is given in the turning plane; "
                                  "program G18 (Z-X) before G{}",
                                  g_number(after.compensation), after.tool, t->srk_lage,
                                  g_number(after.plane), g_number(after.compensation)));
    }
    return true;
}

// Resolves the end point of a move from the axis words and the distance mode.
[[gnu::always_inline]] inline Eigen::Vector3d end_point(const Block& b, const Eigen::Vector3d& from,
                                                         DistanceMode mode) {
    Eigen::Vector3d end = from;
    for (int k = 0; k < 3; ++k) {
        const Word<double>& w = b.axis[static_cast<std::size_t>(k)];
        if (!w.present()) continue;
        end[k] = mode == DistanceMode::kIncremental ? from[k] + w.value : w.value;
    }
    return end;
}

// First column among the words that make the block a move (axis, centre, radius).
std::uint32_t first_motion_column(const Block& b) {
    std::uint32_t col = 0;
    auto take = [&col](const Word<double>& w) {
        if (w.present() && (col == 0 || w.column < col)) col = w.column;
    };
    for (const auto& w : b.axis) take(w);
    for (const auto& w : b.center) take(w);
    take(b.radius);
    return col;
}

bool arc_move(const BlockCheck& c, Plane plane, double feed, Motion motion,
              const Eigen::Vector3d& start, const Eigen::Vector3d& end, ArcMove& out) {
    const Block& b = c.b;
    const PlaneAxes axes = plane_axes(plane);
    const auto n = static_cast<std::size_t>(axes.third);
    if (b.center[n].present()) {
        return c.fail(ErrorKind::kConflict, b.center[n].column,
                      fmt::format("{} is not a centre word in the G{} plane (use {} and {})",
                                  kCenterLetter[n], g_number(plane), kCenterLetter[axes.first],
                                  kCenterLetter[axes.second]));
    }
    // Built in place: on an error the caller drops `out`.
    ArcMove& arc = out;
    arc.start = start;
    arc.end = end;
    arc.ccw = motion == Motion::kArcCcw;
    arc.plane = plane;
    arc.feed = feed;
    if (b.radius.present()) {
        ArcCenterResult r = arc_center_from_radius(start, end, b.radius.value, arc.ccw, plane);
        if (!r.ok) return c.fail(ErrorKind::kGeometry, b.radius.column, std::move(r.message));
        arc.center = r.center;
    } else if (b.has_center_word()) {
        // I/J/K are incremental from the start point in G90 and G91 alike (DIN 66025 practice).
        arc.center = start;
        for (std::size_t k = 0; k < 3; ++k) {
            if (b.center[k].present()) arc.center[static_cast<int>(k)] += b.center[k].value;
        }
        if (!arc_center_ok(start, end, arc.center, plane)) {
            return c.fail(ErrorKind::kGeometry,
                          b.motion.present() ? b.motion.column : first_motion_column(b),
                          check_arc_center(start, end, arc.center, plane));
        }
    } else {
        return c.fail(
            ErrorKind::kProgramRule, first_motion_column(b),
            fmt::format("G{} arc needs its centre ({} {}) or its radius (R)", g_number(motion),
                        kCenterLetter[axes.first], kCenterLetter[axes.second]));
    }
    // Its centre and its path within the board's range, named by the word that placed them.
    if (std::string beyond = check_arc_range(arc, kBoardCoordinateLimit); !beyond.empty()) {
        const std::size_t first = static_cast<std::size_t>(axes.first);
        const std::size_t second = static_cast<std::size_t>(axes.second);
        const std::uint32_t column = b.radius.present()           ? b.radius.column
                                     : b.center[first].present()  ? b.center[first].column
                                     : b.center[second].present() ? b.center[second].column
                                                                  : first_motion_column(b);
        return c.fail(ErrorKind::kValue, column, std::move(beyond));
    }
    return true;
}

// The end point of a move block and, for G2/G3, its arc, with the checks that need them: the
// board's coordinate range, the arc's centre, the move's interpolation cycles. Shared by
// apply_mm and the plain-move path, so that both give the same move or the same error.
[[gnu::always_inline]] inline bool move_geometry(const BlockCheck& c, Motion m, Plane plane,
                                                 DistanceMode distance, double feed,
                                                 const Eigen::Vector3d& from, double cycle_seconds,
                                                 Eigen::Vector3d& end, ArcMove& arc) {
    const Block& b = c.b;
    end = end_point(b, from, distance);
    // The board takes coordinates within +-1e5 (docs/motion.md): a point beyond is refused
    // here, with its word, rather than by the board at the spool.
    for (std::size_t k = 0; k < 3; ++k) {
        if (std::abs(end[static_cast<Eigen::Index>(k)]) <= kBoardCoordinateLimit) continue;
        return c.fail(
            ErrorKind::kValue, b.axis[k].present() ? b.axis[k].column : first_motion_column(b),
            fmt::format("{} {:g} mm is beyond the board's coordinate range of "
                        "+-{:g} mm",
                        kAxisLetter[k], end[static_cast<Eigen::Index>(k)], kBoardCoordinateLimit));
    }
    if (is_arc(m) && !arc_move(c, plane, feed, m, from, end, arc)) return false;
    const bool surely_within =
        m == Motion::kRapid ||
        (m == Motion::kLine ? surely_within_move_cycles(from, end, feed, cycle_seconds)
                            : surely_within_move_cycles(arc, cycle_seconds));
    if (!surely_within) {
        const double length = m == Motion::kLine ? move_length(from, end) : move_length(arc);
        std::string why = check_move_cycles(length, feed, cycle_seconds);
        if (!why.empty())
            return c.fail(ErrorKind::kValue,
                          b.feed.present() ? b.feed.column : first_motion_column(b),
                          std::move(why));
    }
    return true;
}

// A block's move as its event, built in its place in the batch (no copy through a variant):
// from `from` to `end`, `arc` for G2/G3.
[[gnu::always_inline]] inline void push_move(EventBatch& out, const BlockOrigin& origin, Motion m,
                                             const Eigen::Vector3d& from,
                                             const Eigen::Vector3d& end, double feed,
                                             const ArcMove& arc) {
    switch (m) {
        case Motion::kRapid:
            out.push(origin, RapidMove{from, end});
            break;
        case Motion::kLine:
            out.push(origin, LineMove{from, end, feed});
            break;
        case Motion::kArcCw:
        case Motion::kArcCcw:
            out.push(origin, arc);
            break;
    }
}

// The usual block, a move with only N, G0..G3, X Y Z, I J K and F words, whose rules before
// the move all hold: applied as apply_mm would, without copying the modal state (kApplied;
// kFailed with err as apply_mm gives it). kNotPlain, nothing changed: apply_mm. Inline in
// apply(), the one caller.
enum class PlainMove : std::uint8_t { kNotPlain, kApplied, kFailed };
[[gnu::always_inline]] inline PlainMove apply_plain_move(ModalState& state,
                                                         const InterpreterOptions& options,
                                                         const Block& b, std::string_view file,
                                                         EventBatch& out, Diagnostic& err) {
    // Only N, G0..G3, X Y Z, I J K and F: no word that changes another modal group, selects a
    // tool, tilts the head or ends the program.
    if (state.ended || b.plane.present() || b.distance.present() || b.compensation.present() ||
        b.corner.present() || b.selection.present() || b.units.present() || b.tool.present() ||
        b.end_of_program.present() || b.b_axis.present() || b.radius.present() ||
        b.collision.present())
        return PlainMove::kNotPlain;
    const bool center = b.has_center_word();
    if (!center && !b.has_axis_word()) return PlainMove::kNotPlain;
    if (!b.motion.present() && !state.motion) return PlainMove::kNotPlain;
    const Motion m = b.motion.present() ? b.motion.value : *state.motion;
    const double feed = b.feed.present() ? b.feed.value : state.feed;
    // apply_mm's rules before the move, each holding here (else apply_mm names the broken one):
    // centre words only in arcs, a feed for G1..G3, no arc right after a lone G40 under G139.
    if (is_arc(m) ? state.departure_pending : center) return PlainMove::kNotPlain;
    if (m != Motion::kRapid && !(feed > 0.0)) return PlainMove::kNotPlain;
    out.clear();
    const BlockCheck c{b, file, err};
    Eigen::Vector3d end;
    ArcMove arc;
    if (!move_geometry(c, m, state.plane, state.distance, feed, state.position,
                       options.cycle_seconds, end, arc))
        return PlainMove::kFailed;
    // apply_mm's commit for such a block: the motion, the feed, the position; the move is its
    // only event.
    push_move(out, BlockOrigin{b.block_number(), b.line}, m, state.position, end, feed, arc);
    state.motion = m;
    state.feed = feed;
    state.position = end;
    state.departure_pending = false;
    return PlainMove::kApplied;
}

// The modal words of a block into `s`, with the checks on the tool, the plane and the
// cutting edge they must pass.
bool modal_words(const BlockCheck& c, const ModalState& before, const ToolTable* tools,
                 ModalState& s) {
    const Block& b = c.b;
    if (b.motion.present()) s.motion = b.motion.value;
    if (b.distance.present()) s.distance = b.distance.value;
    if (b.feed.present()) s.feed = b.feed.value;
    if (b.corner.present()) s.corner = b.corner.value;
    if (b.collision.present()) s.collision = b.collision.value;
    if (b.selection.present()) s.selection = b.selection.value;
    if (b.compensation.present()) s.compensation = b.compensation.value;
    if (before.trafo && s.compensation != Compensation::kOff &&
        s.compensation != before.compensation) {
        return c.fail(ErrorKind::kProgramRule, b.compensation.column,
                      fmt::format("G{} while #TRAFO is on: radius compensation and the "
                                  "transformation do not combine here; program #TRAFO OFF first",
                                  g_number(s.compensation)));
    }
    if (!check_tool(c, before, tools)) return false;
    if (b.tool.present() && b.tool.value != before.tool) s.tool_wear_const.reset();
    if (b.tool.present()) s.tool = b.tool.value;
    if (!check_plane(c, before, s.compensation)) return false;
    if (b.plane.present()) s.plane = b.plane.value;
    if (s.compensation != Compensation::kOff && s.compensation != before.compensation &&
        !check_cutting_edge(c, s, tools))
        return false;
    return true;
}

// The move of a block with axis, centre, R or B words: its checks (motion mode, feed, words
// of arcs only in arcs, no arc right after G40 or switching compensation, no B in an arc),
// its geometry (`arc` for G2/G3) and its end in `s.position`.
bool block_move(const BlockCheck& c, const ModalState& before, double cycle_seconds,
                ModalState& s, ArcMove& arc) {
    const Block& b = c.b;
    if (!s.motion) {
        return c.fail(ErrorKind::kProgramRule, first_motion_column(b),
                      "no motion mode: program G0, G1, G2 or G3 before the first move");
    }
    const Motion m = *s.motion;
    if (!is_arc(m) && (b.has_center_word() || b.radius.present())) {
        for (std::size_t k = 0; k < 3; ++k) {
            if (b.center[k].present()) {
                return c.fail(ErrorKind::kConflict, b.center[k].column,
                              fmt::format("{} belongs to arcs (G2/G3), not to G{}",
                                          kCenterLetter[k], g_number(m)));
            }
        }
        return c.fail(ErrorKind::kConflict, b.radius.column,
                      fmt::format("R belongs to arcs (G2/G3), not to G{}", g_number(m)));
    }
    if (m != Motion::kRapid && !(s.feed > 0.0)) {
        return c.fail(
            ErrorKind::kProgramRule, first_motion_column(b),
            fmt::format("no feed rate: program F before the first G{} move", g_number(m)));
    }
    // Under G139 (and G138) the move after a lone G40 departs from the last compensated
    // point, r beside the contour: an arc from there would not start where it was programmed
    // ([ISG-PROG] G239: "An arc programmed directly after G40 causes an error message";
    // LinuxCNC: "must be straight, not an arc").
    if (is_arc(m) && before.departure_pending) {
        return c.fail(ErrorKind::kProgramRule,
                      b.motion.present() ? b.motion.column : first_motion_column(b),
                      fmt::format("G{} right after G40: under G{} this move departs from the "
                                  "compensated point, r beside the contour, not from the arc's "
                                  "programmed start; program a G1 (or G0) first, or G40 with "
                                  "G237",
                                  g_number(m), g_number(before.departing)));
    }
    if (is_arc(m) && s.compensation != before.compensation) {
        return c.fail(ErrorKind::kProgramRule, b.compensation.column,
                      fmt::format("G{} switched in an arc block: switch radius compensation "
                                  "with G0/G1 or in a block without a move",
                                  g_number(s.compensation)));
    }
    if (b.b_axis.present() && is_arc(m)) {
        return c.fail(ErrorKind::kProgramRule, b.b_axis.column,
                      "B in an arc block: tilt the head in a G0 or G1 block");
    }
    Eigen::Vector3d end;
    if (!move_geometry(c, m, s.plane, s.distance, s.feed, before.position, cycle_seconds, end,
                       arc))
        return false;
    s.position = end;
    if (b.b_axis.present())
        s.b = s.distance == DistanceMode::kIncremental ? before.b + b.b_axis.value : b.b_axis.value;
    return true;
}

// The events of a block that passed every check, in the documented order.
void push_block_events(const Block& b, const ModalState& before, const ModalState& s, bool moves,
                       const ArcMove& arc, EventBatch& out) {
    const BlockOrigin origin{b.block_number(), b.line};
    if (b.tool.present()) out.push(origin, ToolSelect{b.tool.value});
    if (s.plane != before.plane) out.push(origin, PlaneChange{s.plane});
    // The selection method acts on the G41/G42 or G40 of its own block.
    if (s.selection != before.selection) out.push(origin, SelectionModeChange{s.selection});
    if (s.compensation != before.compensation) out.push(origin, CompensationChange{s.compensation});
    if (b.b_axis.present()) out.push(origin, HeadOrientation{s.b, 0.0});
    if (s.collision != before.collision) out.push(origin, CollisionDetectionChange{s.collision});
    if (moves) push_move(out, origin, *s.motion, before.position, s.position, s.feed, arc);
    // G25/G26 act on the transitions after the block's move ([ISG-PROG]: the transition at
    // the end of the block; [ISG-OTC-EN]'s wr_quad_disc.nc: N80 G26 Y100 leaves the corner
    // before N80 linear), so the change comes after it.
    if (s.corner != before.corner) out.push(origin, CornerModeChange{s.corner});
    if (s.ended) out.push(origin, ProgramEnd{});
}

// The kinematics the emulator knows (docs/design.md section 8; [ISG-OTC] sections 2.4, 2.5 "#KIN ID[4]").
constexpr int kBHeadKinematics = 4;

// #OTC: its settings (not while OTC is on) and OTC on or off.
bool otc_command(const BlockCheck& c, const IsgLine& isg, const ToolTable* tools,
                 const BlockOrigin& origin, ModalState& s, EventBatch& out) {
    const OtcCommand& cmd = isg.otc;
    // [ISG-OTC] section 2.1: "Die Parametrierung kann vorab oder zusammen mit #OTC ON
    // erfolgen": not while OTC is on.
    const bool changes = (cmd.type && *cmd.type != s.otc_type) ||
                         (cmd.mode && *cmd.mode != s.otc_mode) ||
                         (cmd.acc_weight && *cmd.acc_weight != s.otc_acc_weight);
    if (s.otc_active && changes) {
        return c.fail(ErrorKind::kProgramRule, isg.column,
                      "OTC_CHANGE_WHILE_ACTIVE: processing type, mode and ACC_WEIGHT are "
                      "set before or with #OTC ON, not while OTC is on");
    }
    if (cmd.type) s.otc_type = *cmd.type;
    if (cmd.mode) s.otc_mode = *cmd.mode;
    if (cmd.acc_weight) s.otc_acc_weight = *cmd.acc_weight;
    if (cmd.wear_const == WearConstChoice::kProgrammed) {
        s.otc_programmed_wear_const = true;
        s.otc_wear_const = cmd.wear_const_value;
    } else if (cmd.wear_const == WearConstChoice::kTool) {
        s.otc_programmed_wear_const = false;
    }
    if (cmd.on && *cmd.on && !s.otc_active) {
        // [ISG-OTC] section 1: only with tool type 2, else P-ERR-21391. The tool list
        // tells the type; without one the board checks it.
        if (tools != nullptr) {
            const ToolData* t = s.tool > 0 ? tools->find(s.tool) : nullptr;
            const int typ = t != nullptr ? t->typ : 0;
            if (typ != 2) {
                return c.fail(ErrorKind::kProgramRule, isg.column,
                              fmt::format("P-ERR-21391: #OTC ON needs a grinding tool "
                                          "(tool type 2, P-TOOL-00001); D{} is type {}",
                                          s.tool, typ));
            }
        }
        s.otc_active = true;
    } else if (cmd.on && !*cmd.on && s.otc_active) {
        // [ISG-OTC] section 2.2 "Hinweis": G40 before #OTC OFF.
        if (s.otc_type == OtcType::kRadius && s.compensation != Compensation::kOff) {
            return c.fail(ErrorKind::kProgramRule, isg.column,
                          fmt::format("OTC_OFF_BEFORE_G40: #OTC OFF while radius "
                                      "compensation G{} is on: program G40 before #OTC OFF",
                                      g_number(s.compensation)));
        }
        if (s.otc_type == OtcType::kRadius && s.departure_pending) {
            return c.fail(ErrorKind::kProgramRule, isg.column,
                          fmt::format("90050: #OTC OFF right after G40 without a move: "
                                      "under G{} the block after G40 departs from the "
                                      "contour, so program a move (with the G40 or after "
                                      "it) before #OTC OFF",
                                      g_number(s.departing)));
        }
        s.otc_active = false;
    }
    out.push(origin, OtcChange{cmd});
    return true;
}

// #KIN ID[n]: the kinematics (4, the B head, or 0: none).
bool select_kinematics(const BlockCheck& c, const IsgLine& isg, const BlockOrigin& origin,
                       ModalState& s, EventBatch& out) {
    if (isg.kinematics != 0 && isg.kinematics != kBHeadKinematics) {
        return c.fail(ErrorKind::kUnsupported, isg.column,
                      fmt::format("#KIN ID[{}]: kinematics {} is not emulated (ID[4]: the "
                                  "B head, docs/design.md section 8; ID[0]: none)",
                                  isg.kinematics, isg.kinematics));
    }
    if (s.otc_active && isg.kinematics != s.kinematics) {
        return c.fail(ErrorKind::kProgramRule, isg.column,
                      "OTC_CHANGE_WHILE_ACTIVE: #KIN while OTC is on: select the "
                      "kinematics before #OTC ON");
    }
    if (isg.kinematics == 0 && s.trafo) {
        return c.fail(ErrorKind::kProgramRule, isg.column,
                      "#KIN ID[0] while #TRAFO is on: program #TRAFO OFF first");
    }
    s.kinematics = isg.kinematics;
    out.push(origin, KinematicsSelect{isg.kinematics});
    return true;
}

// #TRAFO ON/OFF: the B head's transformation; `tool_length`, that of the tool in force.
bool switch_trafo(const BlockCheck& c, const IsgLine& isg, double tool_length,
                  const BlockOrigin& origin, ModalState& s, EventBatch& out) {
    if (isg.on && s.kinematics == 0) {
        return c.fail(ErrorKind::kProgramRule, isg.column,
                      "#TRAFO ON needs a kinematics: program #KIN ID[4] first");
    }
    if (s.otc_active && isg.on != s.trafo) {
        return c.fail(ErrorKind::kProgramRule, isg.column,
                      "OTC_CHANGE_WHILE_ACTIVE: #TRAFO while OTC is on: switch the "
                      "transformation before #OTC ON or after #OTC OFF");
    }
    if (isg.on && s.compensation != Compensation::kOff) {
        return c.fail(ErrorKind::kProgramRule, isg.column,
                      fmt::format("#TRAFO ON while radius compensation G{} is on: "
                                  "program G40 first (the transformation and radius "
                                  "compensation do not combine here)",
                                  g_number(s.compensation)));
    }
    if (isg.on != s.trafo) {
        // The B head's transformation (docs/design.md section 8, rwmos/geometry/kinematics.h):
        // with it the program gives the tool tip, the pivot one tool length behind it
        // along t(B) = (sin B, 0, cos B). Without it the length acts on the tool axis of
        // the plane (docs/compensation.md "Tool length"): the pivot one length behind the
        // programmed point along that axis. The pivot stays; the position in force
        // changes its meaning (at B0 in G17 it stays the same).
        const double length = tool_length;
        constexpr double kDeg = 3.14159265358979323846 / 180.0;
        const Eigen::Vector3d along_tool =
            length * Eigen::Vector3d(std::sin(s.b * kDeg), 0.0, std::cos(s.b * kDeg));
        Eigen::Vector3d along_axis = Eigen::Vector3d::Zero();
        along_axis[plane_axes(s.plane).third] = length;
        s.position = isg.on ? Eigen::Vector3d(s.position + along_axis - along_tool)
                            : Eigen::Vector3d(s.position + along_tool - along_axis);
        s.trafo_length = length;
    }
    s.trafo = isg.on;
    out.push(origin, TrafoChange{isg.on, s.trafo_length});
    return true;
}

}  // namespace

Interpreter::Interpreter(const InterpreterOptions& options) : options_(options) {
    state_.position = options_.start_position;
}

bool Interpreter::apply(const Block& b, std::string_view file, EventBatch& out, Diagnostic& err) {
    if (!b.units.present() && state_.units == Units::kMetric) {
        const PlainMove plain = apply_plain_move(state_, options_, b, file, out, err);
        if (plain != PlainMove::kNotPlain) return plain == PlainMove::kApplied;
    }
    return apply_general(b, file, out, err);
}

bool Interpreter::apply_general(const Block& b, std::string_view file, EventBatch& out,
                                Diagnostic& err) {
    const Units units = b.units.present() ? b.units.value : state_.units;
    if (units == Units::kMetric) return apply_mm(b, units, file, out, err);
    // G70: every length word and the feed in inches; the events are in mm.
    Block mm = b;
    for (auto& w : mm.axis) w.value *= kMillimetresPerInch;
    for (auto& w : mm.center) w.value *= kMillimetresPerInch;
    mm.radius.value *= kMillimetresPerInch;
    mm.feed.value *= kMillimetresPerInch;
    return apply_mm(mm, units, file, out, err);
}

bool Interpreter::apply_mm(const Block& b, Units units, std::string_view file, EventBatch& out,
                           Diagnostic& err) {
    out.clear();
    const BlockCheck c{b, file, err};
    if (state_.ended) return c.fail(ErrorKind::kProgramRule, 1, std::string(kBlockAfterEnd));
    ModalState s = state_;  // committed only when every check has passed
    s.units = units;
    if (!modal_words(c, state_, options_.tools, s)) return false;

    const bool moves =
        b.has_axis_word() || b.has_center_word() || b.radius.present() || b.b_axis.present();
    if (moves) s.departure_pending = false;
    if (!moves && state_.compensation != Compensation::kOff && s.compensation == Compensation::kOff) {
        // The selection word of the G40's own block decides ([ISG-PROG]: the method acts on
        // the G40 of its block).
        s.departure_pending = s.selection != SelectionMode::kPerpendicular;
        s.departing = s.selection;
    }
    ArcMove arc;  // a G2/G3 block's move, made before the checks that need it
    if (moves && !block_move(c, state_, options_.cycle_seconds, s, arc)) return false;
    if (b.end_of_program.present()) s.ended = true;

    // Every check passed: emit in the documented order and commit.
    push_block_events(b, state_, s, moves, arc, out);
    state_ = s;
    return true;
}

bool Interpreter::apply_isg(const IsgLine& isg, const Block& b, std::string_view file,
                            EventBatch& out, Diagnostic& err) {
    out.clear();
    const BlockCheck c{b, file, err};
    if (state_.ended) return c.fail(ErrorKind::kProgramRule, 1, std::string(kBlockAfterEnd));
    const BlockOrigin origin{b.block_number(), b.line};
    ModalState s = state_;
    switch (isg.kind) {
        case IsgKind::kOtc:
            if (!otc_command(c, isg, options_.tools, origin, s, out)) return false;
            break;
        case IsgKind::kKin:
            if (!select_kinematics(c, isg, origin, s, out)) return false;
            break;
        case IsgKind::kTrafo:
            if (!switch_trafo(c, isg, tool_length_mm(s.tool), origin, s, out)) return false;
            break;
        case IsgKind::kHsc:
            out.push(origin, NotEmulated{"#HSC"});
            break;
        case IsgKind::kFor:
        case IsgKind::kEndFor:
            return c.fail(ErrorKind::kProgramRule, isg.column,
                          "$FOR/$ENDFOR are the program stream's (internal error)");
    }
    state_ = s;
    return true;
}

bool Interpreter::apply_variable_write(const Assignment& a, const Block& b, std::string_view file,
                                       EventBatch& out, Diagnostic& err) {
    out.clear();
    const BlockCheck c{b, file, err};
    if (state_.ended) return c.fail(ErrorKind::kProgramRule, 1, std::string(kBlockAfterEnd));
    if (!variable_writable(a.variable)) {
        return c.fail(ErrorKind::kProgramRule, a.column,
                      fmt::format("{} is read-only", variable_name(a.variable)));
    }
    if (a.variable.variable == NcVariable::kToolTempComp)
        state_.tool_temp_comp[static_cast<std::size_t>(a.variable.index)] = a.value;
    else
        state_.tool_wear_const = a.value;
    out.push(BlockOrigin{b.block_number(), b.line}, VariableWrite{a.variable, a.value});
    return true;
}

double Interpreter::tool_length_mm(int tool) const noexcept {
    const ToolData* t = options_.tools != nullptr && tool > 0 ? options_.tools->find(tool) : nullptr;
    return t != nullptr ? t->length_mm() : 0.0;
}

double Interpreter::model_variable(const VariableRef& v) const noexcept {
    switch (v.variable) {
        case NcVariable::kOtcActive:
            return state_.otc_active ? 1.0 : 0.0;
        case NcVariable::kWearConst: {
            if (state_.tool_wear_const) return *state_.tool_wear_const;
            const ToolData* t = options_.tools != nullptr && state_.tool > 0
                                    ? options_.tools->find(state_.tool)
                                    : nullptr;
            return t != nullptr ? t->grinding_wear_const : 0.0;
        }
        case NcVariable::kToolTempComp:
            return state_.tool_temp_comp[static_cast<std::size_t>(v.index)];
        case NcVariable::kWearRadius:
        case NcVariable::kWearRadiusCont:
        case NcVariable::kWear:
            return 0.0;
    }
    return 0.0;
}

}  // namespace apci::nc
