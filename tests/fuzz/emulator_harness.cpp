// SPDX-License-Identifier: MIT
#include "emulator_harness.h"

#include <array>
#include <bit>
#include <cmath>

#include "objif/dictionary.h"
#include "rwmos/object_map.h"
#include "objif/map/tc_bits.h"

namespace fuzz {

namespace motion = rwmos::motion;
namespace tc = rwmos::tc;
using objif::Status;
using objif::Value;

std::uint16_t ByteSource::u16() noexcept {
    const auto lo = u8();
    return static_cast<std::uint16_t>(lo | (u8() << 8));
}
std::uint32_t ByteSource::u32() noexcept {
    const std::uint32_t lo = u16();
    return lo | (static_cast<std::uint32_t>(u16()) << 16);
}
std::uint64_t ByteSource::u64() noexcept {
    const std::uint64_t lo = u32();
    return lo | (static_cast<std::uint64_t>(u32()) << 32);
}

namespace {

constexpr std::int32_t kTable4Bits = tc::kInitError | tc::kKorrError | tc::kCalcError | tc::kPlaneError |
                                     tc::kCenterError;
constexpr std::int32_t kTable5Bits = tc::kRun | tc::kProfMarked;
constexpr std::int32_t kGroups = 3;

// A coordinate: mostly on a half-unit grid near the origin (where contours
// meet), sometimes wide, sometimes any bit pattern (NaN, huge: refused).
double coordinate(ByteSource& b) {
    switch (b.pick(8)) {
        case 6: return static_cast<double>(static_cast<std::int16_t>(b.u16()));
        case 7: return std::bit_cast<double>(b.u64());
        default: return static_cast<double>(static_cast<std::int8_t>(b.u8())) / 2.0;
    }
}

double feed(ByteSource& b) {
    constexpr std::array<double, 5> kFeeds{0.0, 100.0, 600.0, 6000.0, 60000.0};
    const auto i = b.pick(6);
    return i < kFeeds.size() ? kFeeds[i] : std::bit_cast<double>(b.u64());
}

motion::AxisMask axes(ByteSource& b) {
    constexpr std::array<motion::AxisMask, 3> kMasks{0x03, 0x07, 0x01};
    const auto i = b.pick(4);
    return i < kMasks.size() ? kMasks[i] : b.u8();
}

bool finite(const motion::AxisVector& v) {
    for (double x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

// Every writable (or readable) object row of the dictionary, as the fuzzer picks them.
std::vector<std::pair<std::int32_t, const objif::ObjectInfo*>> rows(rwmos::EmulatedBoard& board, bool writable) {
    std::vector<std::pair<std::int32_t, const objif::ObjectInfo*>> out;
    for (objif::Module* m : board.dictionary().modules()) {
        for (std::size_t i = 0; i < m->object_count(); ++i) {
            const auto& info = m->object_at(i);
            if (writable ? objif::can_write(info.access) : objif::can_read(info.access))
                out.emplace_back(m->bus(), &info);
        }
    }
    return out;
}

}  // namespace

EmulatorHarness::EmulatorHarness(BoardPort& port) : port_(port) {}

std::string EmulatorHarness::run(ByteSource& bytes) {
    for (std::size_t n = 0; n < kMaxSteps && !bytes.empty() && broken_.empty(); ++n) {
        apply(static_cast<Op>(bytes.pick(static_cast<std::uint32_t>(Op::kCount))), bytes);
        if (broken_.empty()) broken_ = check();
    }
    return broken_;
}

void EmulatorHarness::apply(Op op, ByteSource& b) {
    switch (op) {
        case Op::kWrite: write_object(b); break;
        case Op::kRead: read_object(b); break;
        case Op::kSpool: spool(b); break;
        case Op::kDirect: direct(b); break;
        case Op::kSsf: ssf(b); break;
        case Op::kStep: step(b.u16() % 5000); break;
        case Op::kRunUntilIdle: {
            // Sampled cycles cost time each; unsampled ones are advanced analytically.
            const bool sampled = port_.board().motion_status().tracing;
            run_until_idle(sampled ? b.u16() % 20000 : b.u32() % 10'000'000);
            break;
        }
        case Op::kTrace: trace(b); break;
        case Op::kSetUpGroup: set_up_group(b); break;
        case Op::kCount: break;
    }
}

std::optional<std::uint8_t> EmulatorHarness::row_of(const objif::Address& a) {
    const auto all = rows(port_.board(), /*writable=*/true);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const auto& [bus, info] = all[i];
        if (bus == a.bus && info->covers(a)) return static_cast<std::uint8_t>(i);
    }
    return std::nullopt;
}

void EmulatorHarness::write_object(ByteSource& b) {
    const auto all = rows(port_.board(), /*writable=*/true);
    const auto& [bus, info] = all[b.pick(static_cast<std::uint32_t>(all.size()))];
    const auto span = static_cast<std::uint32_t>(info->index_last - info->index_first + 1);
    objif::Descriptor d{{bus, info->device, info->index_first + static_cast<std::int32_t>(b.u8() % span),
                         info->subindex},
                        objif::kNoHandle};
    // The value: small, at a range bound, or any bits; now and then of the other type.
    const auto mode = b.pick(4);
    const bool as_int = (info->type == objif::ValueType::kInt32) != (b.pick(8) == 0);
    Value v;
    if (mode == 1 || mode == 2) {
        const double bound = mode == 1 ? info->min : info->max;
        v = as_int ? Value::of_int(static_cast<std::int32_t>(std::fmax(std::fmin(bound, 2147483647.0), -2147483648.0)))
                   : Value::of_double(bound);
    } else if (mode == 3) {
        v = as_int ? Value::of_int(static_cast<std::int32_t>(b.u32())) : Value::of_double(std::bit_cast<double>(b.u64()));
    } else {
        const auto small = static_cast<std::int8_t>(b.u8());
        v = as_int ? Value::of_int(small) : Value::of_double(small / 4.0);
    }
    note_write(d.address, port_.write(d, v));
}

void EmulatorHarness::read_object(ByteSource& b) {
    const auto all = rows(port_.board(), /*writable=*/false);
    objif::Descriptor d;
    objif::ValueType want = objif::ValueType::kInt32;
    if (b.pick(4) == 0) {
        d.address = {static_cast<std::int16_t>(b.u16()), b.u8(), b.u8(), b.u8()};
        want = b.pick(2) == 0 ? objif::ValueType::kInt32 : objif::ValueType::kDouble;
    } else {
        const auto& [bus, info] = all[b.pick(static_cast<std::uint32_t>(all.size()))];
        d.address = {bus, info->device, info->index_first, info->subindex};
        want = info->type;
    }
    Value v;
    (void)port_.board().read(d, want, v);
}

void EmulatorHarness::spool(ByteSource& b) {
    motion::Profile p;
    p.kind = static_cast<motion::ProfileKind>(b.pick(5) < 4 ? b.pick(4) : b.u8());
    p.tag = next_tag_++;
    p.axes = axes(b);
    for (int i = 0; i < motion::kAxisCount; ++i)
        if ((p.axes >> i) & 1) p.target[static_cast<std::size_t>(i)] = coordinate(b);
    p.feed = feed(b);
    if (motion::is_arc(p.kind)) {
        constexpr std::array<std::array<std::uint8_t, 2>, 3> kArcAxes{{{0, 1}, {1, 0}, {2, 0}}};
        const auto i = b.pick(4);
        p.arc_axes = i < kArcAxes.size() ? kArcAxes[i]
                                         : std::array<std::uint8_t, 2>{static_cast<std::uint8_t>(b.u8() % 9),
                                                                        static_cast<std::uint8_t>(b.u8() % 9)};
        p.center = {coordinate(b), coordinate(b)};
    }
    const motion::MotionResult r = port_.spool(p);
    note_motion(r);
    if (r.ok()) {
        accepted_.insert(p.tag);
        pending_.insert(p.tag);
    }
}

void EmulatorHarness::direct(ByteSource& b) {
    motion::DirectCommand c;
    const auto code = b.pick(3);
    c.code = code == 0 ? motion::DirectCode::kJA
                       : (code == 1 ? motion::DirectCode::kJS : static_cast<motion::DirectCode>(b.u16()));
    c.axes = c.code == motion::DirectCode::kJS && b.pick(4) != 0 ? 0 : axes(b);
    for (int i = 0; i < motion::kAxisCount; ++i)
        if ((c.axes >> i) & 1) c.target[static_cast<std::size_t>(i)] = coordinate(b);
    c.feed = feed(b);
    const motion::MotionResult r = port_.direct(c);
    note_motion(r);
    if (r.ok()) discard_pending();  // a direct command discards the spooler ([APCI-TC] section 1)
}

void EmulatorHarness::ssf(ByteSource& b) {
    const motion::AxisMask mask = axes(b);
    const std::int32_t command = b.pick(4) != 0 ? motion::kSsfReleaseHeldProfile : static_cast<std::int32_t>(b.u32());
    note_motion(port_.ssf(mask, command));
}

void EmulatorHarness::trace(ByteSource& b) {
    rwmos::EmulatedBoard& board = port_.board();
    switch (b.pick(3)) {
        case 0: (void)board.set_trace(true, 1 + b.u8()); break;
        case 1: (void)board.set_trace(false, 0); break;
        default: {
            std::array<motion::TraceSample, 64> samples;
            const std::size_t n = board.read_trace(samples);
            std::uint64_t last = 0;
            for (std::size_t i = 0; i < n; ++i) {
                if (samples[i].cycle <= last) broken_ = "trace samples come in clock order, one per cycle";
                if (samples[i].cycle > board.motion_status().now) broken_ = "no trace sample from the future";
                if (!finite(samples[i].position)) broken_ = "traced axis positions are finite";
                last = samples[i].cycle;
            }
        }
    }
}

void EmulatorHarness::set_up_group(ByteSource& b) {
    // [APCI-TC] section 2.5 "Verwendung von TC": plane axes, tool, radius, side, STATUS = 1.
    const auto group = static_cast<std::int32_t>(1 + b.pick(kGroups));
    const auto tool = static_cast<std::int32_t>(b.pick(4));
    write_tc(tc::kDevGroups, group, tc::kSubXAxis, Value::of_int(0));
    write_tc(tc::kDevGroups, group, tc::kSubYAxis, Value::of_int(1));
    write_tc(tc::kDevGroups, group, tc::kSubWkzIndex, Value::of_int(tool));
    write_tc(tc::kDevGroups, group, tc::kSubRadius, Value::of_double((1 + b.pick(8)) / 2.0));
    write_tc(tc::kDevGroups, group, b.pick(2) == 0 ? tc::kSubLeft : tc::kSubRight, Value::of_int(1));
    write_tc(tc::kDevGroups, group, tc::kSubStatus, Value::of_int(1));
}

void EmulatorHarness::write_tc(std::int32_t device, std::int32_t index, std::int32_t sub, const Value& v) {
    objif::Descriptor d{{tc::kBus, device, index, sub}, objif::kNoHandle};
    note_write(d.address, port_.write(d, v));
}

void EmulatorHarness::step(std::uint64_t cycles) {
    const std::uint64_t before = port_.board().motion_status().now;
    port_.step(cycles);
    if (port_.board().motion_status().now != before + cycles)
        broken_ = "the clock advances by exactly the cycles stepped";
}

void EmulatorHarness::run_until_idle(std::uint64_t max_cycles) {
    const std::uint64_t before = port_.board().motion_status().now;
    const std::uint64_t ran = port_.run_until_idle(max_cycles);
    if (ran > max_cycles) broken_ = "run_until_idle runs at most the cycles allowed";
    if (port_.board().motion_status().now != before + ran)
        broken_ = "the clock advances by exactly the cycles run";
}

void EmulatorHarness::note_write(const objif::Address& a, Status st) {
    if (!objif::ok(st) || a.bus != tc::kBus) return;
    // Reset, RESET and Clean drop the held profile ([APCI-TC] Tables 2 and 3).
    const bool reset = a.device == tc::kDevInit && a.index == tc::kIdxReset;
    const bool clean = a.device == tc::kDevInit && a.index == tc::kIdxClean;
    const bool group_reset = a.device == tc::kDevGroups && a.subindex == tc::kSubReset;
    if (reset || clean || group_reset) discard_pending();
}

void EmulatorHarness::note_motion(const motion::MotionResult& r) {
    if ((r.errors & ~kTable4Bits) != 0) broken_ = "a motion call sets only Table 4 error bits";
    if (r.errors != 0 && r.ok()) broken_ = "a motion call that sets error bits is refused";
    if (r.group < 0 || r.group > kGroups) broken_ = "a motion result names a group 0..3";
}

void EmulatorHarness::discard_pending() { pending_.clear(); }

std::string EmulatorHarness::check() {
    std::string why = check_segments();
    if (why.empty()) why = check_registers();
    if (why.empty()) why = check_motion_status();
    return why;
}

std::string EmulatorHarness::check_registers() {
    rwmos::EmulatedBoard& board = port_.board();
    const motion::MotionStatus st = board.motion_status();
    for (std::int32_t g = 1; g <= kGroups; ++g) {
        objif::Descriptor error_d{{tc::kBus, tc::kDevGroups, g, tc::kSubError}, objif::kNoHandle};
        objif::Descriptor status_d{{tc::kBus, tc::kDevGroups, g, tc::kSubStatus}, objif::kNoHandle};
        Value error, status;
        if (!objif::ok(board.read(error_d, objif::ValueType::kInt32, error)) ||
            !objif::ok(board.read(status_d, objif::ValueType::kInt32, status)))
            return "ERROR and STATUS of every group can be read";
        if ((error.as_int() & ~kTable4Bits) != 0) return "ERROR holds only Table 4 bits";
        if ((status.as_int() & ~kTable5Bits) != 0) return "STATUS holds only Table 5 bits";
        const bool marked = (status.as_int() & tc::kProfMarked) != 0;
        if (marked != (st.profile_held && st.compensating_group == g))
            return "STATUS ProfMarked is set exactly when the group holds a profile";
    }
    return {};
}

std::string EmulatorHarness::check_segments() {
    rwmos::EmulatedBoard& board = port_.board();
    std::array<motion::Segment, 256> segments;
    for (std::size_t n; (n = board.read_segments(segments)) > 0;) {
        for (std::size_t i = 0; i < n; ++i) {
            const motion::Segment& s = segments[i];
            if (!finite(s.start) || !finite(s.end)) return "executed segments have finite end points";
            if (s.tag == 0) {
                if (s.role != motion::SegmentRole::kRapid) return "a segment without a profile is a JA move";
                continue;
            }
            if (accepted_.count(s.tag) == 0) return "every executed segment belongs to an accepted profile";
            // Any segment of a profile shows it ran: a zero-length profile under
            // compensation yields only its (zero-length) approach, no contour.
            pending_.erase(s.tag);
            const bool own = s.role == motion::SegmentRole::kContour ||
                             s.role == motion::SegmentRole::kUncompensated ||
                             s.role == motion::SegmentRole::kRapid;
            if (!own) continue;
            if (ran_.count(s.tag) != 0) return "no profile runs twice";
            if (s.tag < last_ran_) return "profiles run in the order they were spooled";
            ran_.insert(s.tag);
            last_ran_ = s.tag;
        }
    }
    const motion::MotionStatus st = board.motion_status();
    if (st.idle && !st.held && !st.profile_held && st.fill == 0 && st.segments_lost == 0 && !pending_.empty())
        return "no profile lost: once idle, every accepted profile has run or was discarded";
    return {};
}

std::string EmulatorHarness::check_motion_status() {
    rwmos::EmulatedBoard& board = port_.board();
    const motion::MotionStatus st = board.motion_status();
    if (st.now < now_) return "the clock never runs backwards";
    now_ = st.now;
    if (!finite(st.position)) return "axis positions are finite";
    if (st.fill > st.capacity) return "the spooler never holds more than its capacity";
    const auto read_int = [&](std::int32_t index, std::int32_t sub) {
        objif::Descriptor d{{rwmos::board::kBus, rwmos::board::kDevice, index, sub}, objif::kNoHandle};
        Value v;
        return objif::ok(board.read(d, objif::ValueType::kInt32, v)) ? v.as_int() : -1;
    };
    if (read_int(rwmos::board::kIdxSpoolerFill, 0) != static_cast<std::int32_t>(st.fill) ||
        read_int(rwmos::board::kIdxSpoolerCapacity, 0) != static_cast<std::int32_t>(st.capacity))
        return "SpoolerFill and SpoolerCapacity agree with the motion status";
    for (std::int32_t axis = 0; axis < motion::kAxisCount; ++axis) {
        objif::Descriptor d{{rwmos::board::kBus, rwmos::board::kDevice, rwmos::board::kIdxAxisPosition, axis},
                            objif::kNoHandle};
        Value v;
        if (!objif::ok(board.read(d, objif::ValueType::kDouble, v)) || !std::isfinite(v.as_double()))
            return "axis positions are finite";
        if (v.as_double() != st.position[static_cast<std::size_t>(axis)])
            return "the Position objects agree with the motion status";
    }
    return {};
}

}  // namespace fuzz
