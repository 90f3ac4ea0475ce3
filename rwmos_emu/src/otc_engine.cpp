// SPDX-License-Identifier: MIT
// The OTC engine (otc_engine.h; docs/otc.md states every rule with its source).
#include "rwmos/otc_engine.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rwmos/board_state.h"
#include "rwmos/geometry/kinematics.h"

namespace rwmos {

using motion::AxisVector;
using motion::Move;
using motion::SegmentKind;
using motion::SegmentRole;

namespace {

double fraction(std::uint64_t k, std::uint64_t n) noexcept {
    if (n == 0 || k >= n) return 1.0;
    return static_cast<double>(k) / static_cast<double>(n);
}

bool is_contour(const Move& m) noexcept {
    return m.side != 0 && (m.role == SegmentRole::kContour || m.role == SegmentRole::kTransition);
}

std::int32_t to_tenth_um(double length, otc::LengthUnit unit) noexcept {
    const double v = std::round(otc::length_to_tenth_um(length, unit));
    constexpr double kMax = std::numeric_limits<std::int32_t>::max();
    constexpr double kMin = std::numeric_limits<std::int32_t>::min();
    return static_cast<std::int32_t>(std::clamp(v, kMin, kMax));
}

}  // namespace

// ---- Axes and directions

int OtcEngine::sequence_position(int axis) const noexcept {
    for (int i = 0; i < 3; ++i)
        if (session_.xyz[static_cast<std::size_t>(i)] == axis) return i;
    return 3;
}

OtcEngine::Vec3 OtcEngine::to_xyz(const AxisVector& v) const noexcept {
    return {v[static_cast<std::size_t>(session_.xyz[0])],
            v[static_cast<std::size_t>(session_.xyz[1])],
            v[static_cast<std::size_t>(session_.xyz[2])]};
}

void OtcEngine::add_xyz(const Vec3& v, double scale, AxisVector& out) const noexcept {
    for (int i = 0; i < 3; ++i)
        out[static_cast<std::size_t>(session_.xyz[static_cast<std::size_t>(i)])] += scale * v[i];
}

OtcEngine::Vec3 OtcEngine::tool_direction(const AxisVector& nominal) const noexcept {
    // [ISG-OTC] section 2.4: along the tool orientation of the head kinematics; without the
    // transformation the tool stands along the third main axis (design).
    if (session_.tool_from_b)
        return geom::b_head_tool_direction(nominal[static_cast<std::size_t>(session_.b_axis)]);
    return otc::length_direction(0.0, session_.plane);
}

Eigen::Vector2d OtcEngine::contour_normal_at(const Move& m, std::uint64_t k,
                                             std::uint64_t n) const noexcept {
    AxisVector t{};
    motion::tangent_at(m, k, n, t);
    const Eigen::Vector2d tangent{t[static_cast<std::size_t>(session_.plane_axes[0])],
                                  t[static_cast<std::size_t>(session_.plane_axes[1])]};
    return otc::contour_normal(tangent, m.side > 0 ? otc::Side::kLeft : otc::Side::kRight);
}

OtcEngine::Vec3 OtcEngine::surface_normal_at(const Move* m, std::uint64_t k, std::uint64_t n,
                                             const AxisVector& nominal) const noexcept {
    // [ISG-OTC] section 2.5: from the tool direction and the path tangent. Rapid moves grind
    // nothing: the last normal stays (design).
    if (m == nullptr || m->direct || m->traverse || m->role == SegmentRole::kRapid)
        return ctx_.last_surface_normal;
    AxisVector t{};
    motion::tangent_at(*m, k, n, t);
    return otc::surface_normal(tool_direction(nominal), to_xyz(t), ctx_.last_surface_normal);
}

AxisVector OtcEngine::direction(const Move* m, std::uint64_t k, std::uint64_t n,
                                const AxisVector& nominal) const noexcept {
    AxisVector d{};
    switch (session_.type) {
        case otc::ProcessingType::kRadius: {
            // [ISG-OTC] section 2.2: perpendicular to the contour, only with radius compensation;
            // the approach after G41/G42 and the move after G40 are weighed in and out.
            Eigen::Vector2d normal{0, 0};
            double weight = 0.0;
            if (m == nullptr) {
                normal = ctx_.end_normal;
                weight = ctx_.end_weight;
            } else {
                switch (ctx_.blend) {
                    case Blend::kNone:
                        break;
                    case Blend::kFull:
                        normal = contour_normal_at(*m, k, n);
                        weight = 1.0;
                        break;
                    case Blend::kIn:
                        normal = ctx_.fixed_normal;
                        weight = fraction(k, n);
                        break;
                    case Blend::kOut:
                        normal = ctx_.fixed_normal;
                        weight = ctx_.out_weight * (1.0 - fraction(k, n));
                        break;
                }
            }
            d[static_cast<std::size_t>(session_.plane_axes[0])] = weight * normal.x();
            d[static_cast<std::size_t>(session_.plane_axes[1])] = weight * normal.y();
            break;
        }
        case otc::ProcessingType::kLength:
            add_xyz(session_.length_direction, 1.0, d);
            break;
        case otc::ProcessingType::kToolDir:
            add_xyz(tool_direction(nominal), 1.0, d);
            break;
        case otc::ProcessingType::kSurfNormDir:
            add_xyz(surface_normal_at(m, k, n, nominal), 1.0, d);
            break;
    }
    return d;
}

double OtcEngine::wear_at(const Move* m, std::uint64_t k, std::uint64_t n) const noexcept {
    if (m == nullptr) return wear_;
    return ctx_.wear_start + ctx_.wear_per_fraction * fraction(k, n);
}

// ---- Control units

double OtcEngine::channel_command() const noexcept {
    const OtcState& o = state_.otc;
    if (!o.active || !o.radius_offset_unit.enable ||
        !otc::channel_unit_acts(session_.type, session_.mode))
        return 0.0;
    return otc::tenth_um_to_length(o.radius_offset_unit.command, session_.unit);
}

double OtcEngine::direction_command() const noexcept {
    const OtcState& o = state_.otc;
    if (!o.active) return 0.0;
    const int third = session_.xyz[2];
    const OtcControlUnit& u = o.axis_units[static_cast<std::size_t>(third)];
    if (!u.enable ||
        otc::axis_unit_role(session_.type, session_.mode, 2) != otc::AxisUnitRole::kDirection)
        return 0.0;
    return otc::tenth_um_to_length(u.command, session_.unit);
}

double OtcEngine::axis_command(int axis) const noexcept {
    const OtcState& o = state_.otc;
    if (!o.active) return 0.0;
    const OtcControlUnit& u = o.axis_units[static_cast<std::size_t>(axis)];
    if (!u.enable || otc::axis_unit_role(session_.type, session_.mode, sequence_position(axis)) !=
                         otc::AxisUnitRole::kAxis)
        return 0.0;
    return otc::tenth_um_to_length(u.command, session_.unit);
}

OtcEngine::Targets OtcEngine::targets(const AxisVector& dir) const noexcept {
    Targets t;
    const double ch = channel_command();
    const double dc = direction_command();
    for (std::size_t a = 0; a < t.axes.size(); ++a) {
        t.channel[a] = ch == 0.0 ? 0.0 : -ch * dir[a];
        t.direction[a] = dc == 0.0 ? 0.0 : -dc * dir[a];
        t.axes[a] = -axis_command(static_cast<int>(a)) + standing_[a];
    }
    return t;
}

OtcEngine::Targets OtcEngine::targets_now(const AxisVector& dir) const noexcept {
    if (state_.otc.active) return targets(dir);
    Targets t;
    t.axes = standing_;
    return t;
}

otc::RampLimits OtcEngine::limits() const noexcept {
    const OtcState& o = state_.otc;
    return {o.ramp_velocity, otc::weighted_acceleration(o.ramp_acceleration, o.acc_weight)};
}

bool OtcEngine::ramps_settled() const noexcept {
    const AxisVector nominal = state_.motion.executor().nominal_position();
    const Targets t =
        targets_now(state_.otc.active ? direction(nullptr, 0, 0, nominal) : AxisVector{});
    for (std::size_t a = 0; a < t.axes.size(); ++a)
        if (!otc::settled(ramp_channel_[a], t.channel[a]) ||
            !otc::settled(ramp_direction_[a], t.direction[a]) ||
            !otc::settled(ramp_axes_[a], t.axes[a]))
            return false;
    return true;
}

bool OtcEngine::direction_turns(const Move* m) const noexcept {
    if (m == nullptr || (channel_command() == 0.0 && direction_command() == 0.0)) return false;
    const bool b_turns =
        session_.tool_from_b && m->start[static_cast<std::size_t>(session_.b_axis)] !=
                                    m->end[static_cast<std::size_t>(session_.b_axis)];
    switch (session_.type) {
        case otc::ProcessingType::kRadius:
            return ctx_.blend == Blend::kIn || ctx_.blend == Blend::kOut ||
                   (ctx_.blend == Blend::kFull && m->kind == SegmentKind::kArc);
        case otc::ProcessingType::kLength:
            return false;
        case otc::ProcessingType::kToolDir:
            return b_turns;
        case otc::ProcessingType::kSurfNormDir:
            return b_turns || m->kind == SegmentKind::kArc;
    }
    return true;
}

std::int32_t OtcEngine::channel_request() const noexcept {
    return channel_command() == 0.0 ? 0 : state_.otc.radius_offset_unit.command;
}

std::int32_t OtcEngine::axis_request(int axis) const noexcept {
    const std::int32_t cmd = state_.otc.axis_units[static_cast<std::size_t>(axis)].command;
    if (state_.otc.active && axis == session_.xyz[2] && direction_command() != 0.0) return cmd;
    return axis_command(axis) == 0.0 ? 0 : cmd;
}

namespace {
// How far a ramp vector has come along `dir` (0 when there is no direction).
double along(const std::array<otc::RampState, kOtcAxisCount>& ramp,
             const AxisVector& dir) noexcept {
    double dot = 0.0, norm = 0.0;
    for (std::size_t a = 0; a < ramp.size(); ++a) {
        dot += ramp[a].position * dir[a];
        norm += dir[a] * dir[a];
    }
    return norm == 0.0 ? 0.0 : -dot / std::sqrt(norm);
}
}  // namespace

std::int32_t OtcEngine::channel_state() const noexcept {
    return to_tenth_um(along(ramp_channel_, last_dir_), session_.unit);
}

std::int32_t OtcEngine::axis_state(int axis) const noexcept {
    const auto a = static_cast<std::size_t>(axis);
    if (state_.otc.active && axis == session_.xyz[2] &&
        otc::axis_unit_role(session_.type, session_.mode, 2) == otc::AxisUnitRole::kDirection)
        return to_tenth_um(along(ramp_direction_, last_dir_), session_.unit);
    return to_tenth_um(-ramp_axes_[a].position, session_.unit);
}

// ---- Session

void OtcEngine::start_session() noexcept {
    const OtcState& o = state_.otc;
    const TcState& tc = state_.tc;
    session_.type = o.type;
    session_.mode = o.mode;
    session_.plane = geom::plane_from_code(tc.plane).value_or(geom::Plane::kXY);
    session_.xyz = {tc.axis_nr[0], tc.axis_nr[1], tc.axis_nr[2]};
    const geom::PlaneAxes pa = geom::plane_axes(session_.plane);
    session_.plane_axes = {session_.xyz[static_cast<std::size_t>(pa.first)],
                           session_.xyz[static_cast<std::size_t>(pa.second)]};
    // The offsets act on positions, which are mm whatever PU says (PU is the unit of the TC
    // tool values only, docs/object-map.md section 2).
    session_.unit = otc::LengthUnit::kMillimetre;
    session_.length_direction =
        otc::length_direction(otc::tilt_to_degrees(o.tool.tilt_angle), session_.plane);
    session_.tool_from_b = o.kinematics == geom::kBHeadKinematicsId && o.trafo;
    session_.b_axis = o.tool_axis_b;
    ctx_ = Context{};
    ctx_.last_surface_normal = tool_direction(state_.motion.executor().nominal_position());
    have_last_ = false;
    wear_ = 0.0;
}

void OtcEngine::end_session() noexcept {
    OtcState& o = state_.otc;
    const AxisVector nominal = state_.motion.executor().nominal_position();
    const AxisVector dir = direction(nullptr, 0, 0, nominal);
    const double w = wear_;
    const double d_channel = channel_command();
    const double d_direction = direction_command();
    AxisVector d_axes{};
    for (std::size_t a = 0; a < d_axes.size(); ++a) d_axes[a] = axis_command(static_cast<int>(a));

    // [ISG-OTC] section 2.1 "Hinweis": "Mit Abwahl der OTC durch #OTC OFF wird der aufgetretene
    // Verschleiß (diskret und/oder kontinuierlich) in das aktuelle Werkzeug eingerechnet"; section
    // 2.8: the variables hold the wear since the tool came in, accumulated over ON/OFF.
    double fold_radius = 0.0, fold_length = 0.0;
    AxisVector unit_dir = dir;
    double norm = 0.0;
    for (double v : unit_dir) norm += v * v;
    if (norm > 0.0)
        for (double& v : unit_dir) v /= std::sqrt(norm);
    switch (session_.type) {
        case otc::ProcessingType::kRadius:
            o.wear.radius += w + d_channel;
            o.wear.radius_cont += w;
            for (std::size_t a = 0; a < d_axes.size(); ++a) o.wear.axis[a] += d_axes[a];
            fold_radius = w + d_channel;
            break;
        case otc::ProcessingType::kLength:
            fold_length = w;
            for (std::size_t a = 0; a < d_axes.size(); ++a) {
                o.wear.axis[a] += w * unit_dir[a] + d_axes[a];
                fold_length += d_axes[a] * unit_dir[a];
            }
            break;
        case otc::ProcessingType::kToolDir:
        case otc::ProcessingType::kSurfNormDir: {
            const double s = w + d_direction + d_channel;
            for (std::size_t a = 0; a < d_axes.size(); ++a)
                o.wear.axis[a] += s * unit_dir[a] + d_axes[a];
            // Along the tool a worn disc is shorter; along the surface normal its rim is smaller.
            if (session_.type == otc::ProcessingType::kToolDir)
                fold_length = s;
            else
                fold_radius = s;
            break;
        }
    }
    // Where the folded length acts on an axis now (the tool length on every profile, LengthMode
    // 1, or the group compensating) and the wear points along +Z of the TC plane (the way WkzLen
    // acts), the offset's part on that axis passes into the tool length without a motion: the
    // nominal path takes it (the next profile has the shorter tool) and that axis ramps only
    // what had not yet arrived. So repeated passes add up. WkzLen then shrinks by that part
    // (a disc tilted by a: the wear times cos a); the part across the axis (a tilted disc's X)
    // stays on its axes as a standing offset while the tool is in (docs/otc.md section 6).
    AxisVector stays{};
    double folded_length = fold_length;
    const int length_axis = state_.motion.length_axis_of(o.tool.number);
    if (fold_length != 0.0 && length_axis >= 0 && norm > 0.0) {
        const auto z = static_cast<std::size_t>(length_axis);
        // The offsets the session's targets held on each axis: the wear along the direction,
        // the channel's, the direction's and the axes' commands.
        const Targets held = targets(dir);
        AxisVector offset{};
        for (std::size_t a = 0; a < offset.size(); ++a)
            offset[a] =
                -w * dir[a] + held.channel[a] + held.direction[a] + held.axes[a] - standing_[a];
        const double along = -offset[z];
        if (unit_dir[z] > 1e-12 && state_.motion.shift_length(length_axis, -along)) {
            stays[z] = -along;
            folded_length = along;
            for (std::size_t a = 0; a < offset.size(); ++a)
                if (a != z) standing_[a] += offset[a];
        }
    }
    const auto tool = static_cast<std::size_t>(o.tool.number);
    for (TcGroup& g : state_.tc.groups) {
        TcTool& t = g.tools[tool];
        // The wear is mm; the tool values are kept in the unit PU selects.
        t.radius = std::max(0.0, t.radius - board::millimetres_to_pu(fold_radius, state_.pu));
        t.length -= board::millimetres_to_pu(folded_length, state_.pu);
    }
    state_.motion.settings_changed();  // the tool table the TC settings read

    // The offsets now on the axes ramp out from where they are: never a jump.
    for (std::size_t a = 0; a < ramp_axes_.size(); ++a) {
        ramp_axes_[a].position +=
            -w * dir[a] - stays[a] + ramp_channel_[a].position + ramp_direction_[a].position;
        ramp_axes_[a].velocity += ramp_channel_[a].velocity + ramp_direction_[a].velocity;
        ramp_channel_[a] = {};
        ramp_direction_[a] = {};
    }
    ramps_quiet_ = ramps_at_rest();
    // The discrete infeed is consumed by the fold (design: P-TOOL-00031 is the largest
    // "relative Änderung"; the next session starts from a command of 0).
    o.radius_offset_unit.command = 0;
    for (OtcControlUnit& u : o.axis_units) u.command = 0;
    wear_ = 0.0;
    ctx_ = Context{};
    have_last_ = false;
    last_dir_ = {};
}

void OtcEngine::wear_const_changed(double before) noexcept {
    const MotionLayer& motion = state_.motion;
    if (wear_const_changes_.empty()) wear_const_before_ = before;
    // Changes whose profile every move still to run has reached hold for all of them.
    const std::uint64_t oldest = motion.oldest_profile_in_flight();
    const auto held = std::find_if(wear_const_changes_.begin(), wear_const_changes_.end(),
                                   [&](const WearConstChange& c) { return c.from > oldest; });
    for (auto at = wear_const_changes_.begin(); at != held; ++at) wear_const_before_ = at->value;
    wear_const_changes_.erase(wear_const_changes_.begin(), held);
    const WearConstChange now{motion.next_profile(), state_.otc.effective_wear_const()};
    if (now.from <= oldest) {
        // Nothing in flight: it holds for every move from here on.
        wear_const_changes_.clear();
        wear_const_before_ = now.value;
    } else if (!wear_const_changes_.empty() && wear_const_changes_.back().from == now.from) {
        wear_const_changes_.back().value = now.value;  // several writes between two profiles
    } else {
        wear_const_changes_.push_back(now);
    }
}

double OtcEngine::wear_const_for(std::uint64_t profile) noexcept {
    std::size_t done = 0;
    while (done < wear_const_changes_.size() && wear_const_changes_[done].from <= profile)
        wear_const_before_ = wear_const_changes_[done++].value;
    wear_const_changes_.erase(wear_const_changes_.begin(),
                              wear_const_changes_.begin() + static_cast<std::ptrdiff_t>(done));
    return wear_const_changes_.empty() ? state_.otc.effective_wear_const() : wear_const_before_;
}

void OtcEngine::tool_changed() noexcept {
    state_.otc.wear = OtcWear{};
    // The tool that goes out takes its standing offsets with it (the ramps run them off).
    standing_ = {};
    ramps_quiet_ = ramps_at_rest();
}

// ---- motion::CycleOffsets

namespace {
// Path length on the main axes X, Y, Z only (a B move tilts, it does not grind), on the
// programmed path: a tool length coming in or going out moves the axes, it does not grind.
double main_axes_length(const Move& m, const std::array<int, 3>& xyz) noexcept {
    double other = 0.0;
    double plane = 0.0;
    bool arc_in_main = false;
    if (m.kind == SegmentKind::kArc) {
        const auto in_xyz = [&](int axis) {
            return axis == xyz[0] || axis == xyz[1] || axis == xyz[2];
        };
        arc_in_main = in_xyz(m.plane_axes[0]) && in_xyz(m.plane_axes[1]);
        if (arc_in_main) plane = motion::arc_plane_length(m);
    }
    for (int axis : xyz) {
        if (arc_in_main && (axis == m.plane_axes[0] || axis == m.plane_axes[1])) continue;
        const auto a = static_cast<std::size_t>(axis);
        const double d = m.end[a] - m.start[a] - m.length_change[a];
        other += d * d;
    }
    return std::sqrt(plane * plane + other);
}
}  // namespace

void OtcEngine::move_started(const Move& m, const Move* next) noexcept {
    if (!state_.otc.active) return;
    ctx_.wear_start = wear_;
    // [ISG-OTC] section 2: "Eilgangssätze sind verschleißfrei!" (G00, JA jogs, and a G00 on the
    // compensated path, a traverse); section 2.2: the approach after G41/G42 and the move after
    // G40 are wear-free; RADIUS wears only with radius compensation.
    const bool wears = otc::mode_has_continuous(session_.mode) && !m.direct && !m.traverse &&
                       m.role != SegmentRole::kRapid && m.role != SegmentRole::kApproach &&
                       m.role != SegmentRole::kDeparture &&
                       (session_.type != otc::ProcessingType::kRadius || is_contour(m));
    ctx_.wear_per_fraction = wears ? otc::continuous_wear(main_axes_length(m, session_.xyz),
                                                          wear_const_for(m.profile))
                                   : 0.0;
    if (session_.type == otc::ProcessingType::kRadius) {
        const double carried = have_last_ ? ctx_.end_weight : 0.0;
        if (is_contour(m)) {
            ctx_.blend = Blend::kFull;
        } else if (m.side != 0 && m.role == SegmentRole::kApproach && next != nullptr &&
                   is_contour(*next)) {
            ctx_.blend = Blend::kIn;
            ctx_.fixed_normal = contour_normal_at(*next, 0, 1);
        } else if (carried > 0.0) {
            ctx_.blend = Blend::kOut;
            ctx_.fixed_normal = ctx_.end_normal;
            ctx_.out_weight = carried;
        } else {
            ctx_.blend = Blend::kNone;
        }
    }
}

void OtcEngine::move_finished(const Move& m, std::uint64_t k, std::uint64_t n) noexcept {
    if (!state_.otc.active) return;
    wear_ = ctx_.wear_start + ctx_.wear_per_fraction * fraction(k, n);
    ctx_.wear_per_fraction = 0.0;
    ctx_.wear_start = wear_;
    const double f = fraction(k, n);
    switch (ctx_.blend) {
        case Blend::kNone:
            ctx_.end_weight = 0.0;
            break;
        case Blend::kFull:
            ctx_.end_normal = contour_normal_at(m, k, n);
            ctx_.end_weight = 1.0;
            break;
        case Blend::kIn:
            ctx_.end_normal = ctx_.fixed_normal;
            ctx_.end_weight = f;
            break;
        case Blend::kOut:
            ctx_.end_normal = ctx_.fixed_normal;
            ctx_.end_weight = ctx_.out_weight * (1.0 - f);
            break;
    }
    if (session_.type == otc::ProcessingType::kSurfNormDir) {
        AxisVector end{};
        motion::position_at(m, k, n, end);
        ctx_.last_surface_normal = surface_normal_at(&m, k, n, end);
    }
    last_move_ = m;
    have_last_ = true;
}

bool OtcEngine::per_cycle(const Move* m, std::uint64_t k, std::uint64_t n) const noexcept {
    // Off with every ramp at rest at 0: the targets are 0 and settled, nothing to step (the
    // same answer as below, without its position and 24 ramp checks per move).
    if (!state_.otc.active && ramps_quiet_) return false;
    AxisVector nominal{};
    if (m != nullptr)
        motion::position_at(*m, k == 0 && n == 0 ? 1 : k, n == 0 ? 1 : n, nominal);
    else
        nominal = state_.motion.executor().nominal_position();
    const Targets t = targets_now(state_.otc.active ? direction(m, k, n, nominal) : AxisVector{});
    for (std::size_t a = 0; a < t.axes.size(); ++a)
        if (!otc::settled(ramp_channel_[a], t.channel[a]) ||
            !otc::settled(ramp_direction_[a], t.direction[a]) ||
            !otc::settled(ramp_axes_[a], t.axes[a]))
            return true;
    return state_.otc.active && direction_turns(m);
}

bool OtcEngine::inert() const noexcept {
    // move_started / move_finished return at once while off; per_cycle is false while off and
    // quiet; at() then adds the resting ramp positions (step() alone moves them).
    return !state_.otc.active && ramps_quiet_;
}

void OtcEngine::add_offsets(const AxisVector& dir, double wear, AxisVector& pos) const noexcept {
    for (std::size_t a = 0; a < pos.size(); ++a)
        pos[a] += -wear * dir[a] + ramp_channel_[a].position + ramp_direction_[a].position +
                  ramp_axes_[a].position;
}

bool OtcEngine::ramps_at_rest() const noexcept {
    const auto rest = [](const otc::RampState& r, double at) {
        return r.position == at && r.velocity == 0.0;
    };
    for (std::size_t a = 0; a < ramp_axes_.size(); ++a) {
        if (!rest(ramp_channel_[a], 0.0) || !rest(ramp_direction_[a], 0.0) ||
            !rest(ramp_axes_[a], standing_[a]))
            return false;
    }
    return true;
}

void OtcEngine::step(const Move* m, std::uint64_t k, std::uint64_t n, double dt,
                     AxisVector& pos) noexcept {
    const AxisVector dir = state_.otc.active ? direction(m, k, n, pos) : AxisVector{};
    last_dir_ = dir;
    // OTC off and every ramp at rest on its target 0: ramp_step would return
    // each state unchanged, so the (per-cycle, 24-ramp) loop is skipped.
    if (!state_.otc.active && ramps_quiet_) {
        add_offsets(dir, 0.0, pos);
        return;
    }
    const Targets t = targets_now(dir);
    const otc::RampLimits lim = limits();
    for (std::size_t a = 0; a < t.axes.size(); ++a) {
        ramp_channel_[a] = otc::ramp_step(ramp_channel_[a], t.channel[a], lim, dt);
        ramp_direction_[a] = otc::ramp_step(ramp_direction_[a], t.direction[a], lim, dt);
        ramp_axes_[a] = otc::ramp_step(ramp_axes_[a], t.axes[a], lim, dt);
    }
    ramps_quiet_ = !state_.otc.active && ramps_at_rest();
    add_offsets(dir, state_.otc.active ? wear_at(m, k, n) : 0.0, pos);
}

void OtcEngine::at(const Move* m, std::uint64_t k, std::uint64_t n,
                   AxisVector& pos) const noexcept {
    if (!state_.otc.active) {
        // add_offsets with no direction and no wear: -0.0 * 0.0 is -0.0, the identity of +.
        last_dir_ = AxisVector{};
        for (std::size_t a = 0; a < pos.size(); ++a)
            pos[a] +=
                ramp_channel_[a].position + ramp_direction_[a].position + ramp_axes_[a].position;
        return;
    }
    const AxisVector dir = state_.otc.active ? direction(m, k, n, pos) : AxisVector{};
    last_dir_ = dir;
    add_offsets(dir, state_.otc.active ? wear_at(m, k, n) : 0.0, pos);
}

}  // namespace rwmos
