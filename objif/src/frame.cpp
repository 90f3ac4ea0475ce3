// SPDX-License-Identifier: MIT
#include "objif/frame.h"

#include "objif/byte_order.h"
#include "objif/enum_names.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <ctime>

namespace objif {

bool opcode_known(std::uint16_t op) noexcept {
    return op >= static_cast<std::uint16_t>(Opcode::kObjectRead) &&
           op <= static_cast<std::uint16_t>(Opcode::kMotionClaim);
}

std::string_view opcode_name(std::uint16_t op) noexcept {
    const bool reply = (op & kReplyFlag) != 0 && op != static_cast<std::uint16_t>(kReplyFlag | 0x7FFF);
    switch (static_cast<Opcode>(op & ~kReplyFlag)) {
        case Opcode::kObjectRead: return reply ? "ObjectReadReply" : "ObjectRead";
        case Opcode::kObjectWrite: return reply ? "ObjectWriteReply" : "ObjectWrite";
        case Opcode::kSpoolProfile: return reply ? "SpoolProfileReply" : "SpoolProfile";
        case Opcode::kDirectCommand: return reply ? "DirectCommandReply" : "DirectCommand";
        case Opcode::kSsfCommand: return reply ? "SsfCommandReply" : "SsfCommand";
        case Opcode::kClock: return reply ? "ClockReply" : "Clock";
        case Opcode::kReadTrace: return reply ? "ReadTraceReply" : "ReadTrace";
        case Opcode::kMotionClaim: return reply ? "MotionClaimReply" : "MotionClaim";
        case Opcode::kNotice:
            return "Notice";
        case Opcode::kError: return "Error";
    }
    return "Unknown";
}

std::string_view frame_error_name(FrameError e) noexcept {
    static constexpr auto kNames = enum_names<FrameError::kNone, FrameError::kNotFinite>(
        {"none", "short frame", "bad magic", "bad version", "bad payload length", "bad CRC",
         "unknown opcode", "bad payload for opcode", "bad value tag", "value is NaN or infinite"},
        "unknown frame error");
    return kNames(e);
}

Status frame_error_status(FrameError e) noexcept {
    switch (e) {
        case FrameError::kNone: return Status::kOk;
        case FrameError::kUnknownOpcode: return Status::kUnknownOpcode;
        case FrameError::kBadValueTag: return Status::kTypeMismatch;
        case FrameError::kNotFinite: return Status::kInvalidValue;
        default: return Status::kBadFrame;
    }
}

namespace {
std::uint32_t crc32_of(const std::uint8_t* p, std::size_t n) {
    return static_cast<std::uint32_t>(::crc32(0L, p, static_cast<uInt>(n)));
}
// The wire is little-endian (docs/wire-frame.md) on every host.
template <class T>
T load(const std::uint8_t* p) {
    return load_little<T>(p);
}
}  // namespace

void encode_frame(std::uint16_t opcode, std::uint32_t sequence,
                  std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out) {
    const std::size_t start = out.size();
    ByteWriter w(out);
    w.u32(kFrameMagic);
    w.u16(kFrameVersion);
    w.u16(opcode);
    w.u32(sequence);
    w.u32(static_cast<std::uint32_t>(payload.size()));
    out.insert(out.end(), payload.begin(), payload.end());
    w.u32(crc32_of(out.data() + start, out.size() - start));
}

FrameError decode_frame(std::span<const std::uint8_t> bytes, Frame& out, std::size_t& consumed,
                        bool& need_more) {
    consumed = 0;
    need_more = false;
    const std::uint8_t* p = bytes.data();
    const std::size_t n = bytes.size();
    // Check what is there as soon as it is there, so garbage is refused early.
    if (n >= 4 && load<std::uint32_t>(p) != kFrameMagic) return FrameError::kBadMagic;
    if (n > 0 && n < 4) {
        // A prefix of the magic is still a valid prefix (an empty one too).
        std::uint8_t magic[4];
        store_little(magic, kFrameMagic);
        if (std::memcmp(p, magic, n) != 0) return FrameError::kBadMagic;
    }
    if (n >= 6 && load<std::uint16_t>(p + 4) != kFrameVersion) return FrameError::kBadVersion;
    if (n < kFrameHeaderSize) {
        need_more = true;
        return FrameError::kShort;
    }
    const auto length = load<std::uint32_t>(p + 12);
    if (length > kMaxPayload) return FrameError::kBadLength;
    const std::size_t total = kFrameHeaderSize + length + kFrameCrcSize;
    if (n < total) {
        need_more = true;
        return FrameError::kShort;
    }
    // From here on the frame's boundary is known: a stream can skip it.
    consumed = total;
    out.opcode = load<std::uint16_t>(p + 6);
    out.sequence = load<std::uint32_t>(p + 8);
    const auto crc = load<std::uint32_t>(p + kFrameHeaderSize + length);
    if (crc != crc32_of(p, kFrameHeaderSize + length)) return FrameError::kBadCrc;
    const auto base = static_cast<std::uint16_t>(out.opcode & ~kReplyFlag);
    if (!opcode_known(base) && base != static_cast<std::uint16_t>(Opcode::kError) &&
        base != static_cast<std::uint16_t>(Opcode::kNotice))
        return FrameError::kUnknownOpcode;
    out.payload.assign(p + kFrameHeaderSize, p + kFrameHeaderSize + length);
    return FrameError::kNone;
}

// ---- ByteWriter / ByteReader

namespace {
template <class T>
void put_little(std::vector<std::uint8_t>& out, T v) {
    std::uint8_t bytes[sizeof v];
    store_little(bytes, v);
    out.insert(out.end(), bytes, bytes + sizeof v);
}
}  // namespace

void ByteWriter::u16(std::uint16_t v) { put_little(out_, v); }
void ByteWriter::u32(std::uint32_t v) { put_little(out_, v); }
void ByteWriter::u64(std::uint64_t v) { put_little(out_, v); }
void ByteWriter::f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
void ByteWriter::value(const Value& v) {
    u8(static_cast<std::uint8_t>(v.type()));
    if (v.is_int())
        i32(v.as_int());
    else
        f64(v.as_double());
}
void ByteWriter::address(const Address& a) {
    i32(a.bus);
    i32(a.device);
    i32(a.index);
    i32(a.subindex);
}
void ByteWriter::descriptor(const Descriptor& d) {
    address(d.address);
    u32(d.handle);
}

template <class T>
static bool take(std::span<const std::uint8_t> in, std::size_t& pos, T& v) {
    if (in.size() - pos < sizeof(T)) return false;
    v = load_little<T>(in.data() + pos);
    pos += sizeof(T);
    return true;
}
bool ByteReader::u8(std::uint8_t& v) { return take(in_, pos_, v); }
bool ByteReader::u16(std::uint16_t& v) { return take(in_, pos_, v); }
bool ByteReader::u32(std::uint32_t& v) { return take(in_, pos_, v); }
bool ByteReader::i32(std::int32_t& v) {
    std::uint32_t bits = 0;
    if (!take(in_, pos_, bits)) return false;
    v = static_cast<std::int32_t>(bits);
    return true;
}
bool ByteReader::u64(std::uint64_t& v) { return take(in_, pos_, v); }
bool ByteReader::f64(double& v) {
    std::uint64_t bits;
    if (!u64(bits)) return false;
    v = std::bit_cast<double>(bits);
    return true;
}
FrameError ByteReader::value(Value& v) {
    std::uint8_t tag;
    if (!u8(tag)) return FrameError::kBadPayload;
    if (tag == static_cast<std::uint8_t>(ValueType::kInt32)) {
        std::int32_t i;
        if (!i32(i)) return FrameError::kBadPayload;
        v = Value::of_int(i);
        return FrameError::kNone;
    }
    if (tag == static_cast<std::uint8_t>(ValueType::kDouble)) {
        double d;
        if (!f64(d)) return FrameError::kBadPayload;
        if (!std::isfinite(d)) return FrameError::kNotFinite;
        v = Value::of_double(d);
        return FrameError::kNone;
    }
    return FrameError::kBadValueTag;
}
bool ByteReader::address(Address& a) {
    return i32(a.bus) && i32(a.device) && i32(a.index) && i32(a.subindex);
}
bool ByteReader::descriptor(Descriptor& d) { return address(d.address) && u32(d.handle); }

// ---- Payloads

static bool type_tag_ok(std::uint8_t t) {
    return t == static_cast<std::uint8_t>(ValueType::kInt32) ||
           t == static_cast<std::uint8_t>(ValueType::kDouble);
}

void encode(const ReadRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.descriptor(m.descriptor);
    w.u8(static_cast<std::uint8_t>(m.want));
}
FrameError decode(std::span<const std::uint8_t> p, ReadRequest& m) {
    ByteReader r(p);
    std::uint8_t want;
    if (!r.descriptor(m.descriptor) || !r.u8(want) || !r.done()) return FrameError::kBadPayload;
    if (!type_tag_ok(want)) return FrameError::kBadValueTag;
    m.want = static_cast<ValueType>(want);
    return FrameError::kNone;
}

void encode(const ReadReply& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    w.u32(m.handle);
    if (ok(m.status)) w.value(m.value);
}
FrameError decode(std::span<const std::uint8_t> p, ReadReply& m) {
    ByteReader r(p);
    std::uint32_t code;
    if (!r.u32(code) || !r.u32(m.handle)) return FrameError::kBadPayload;
    if (!status_from_code(code, m.status)) return FrameError::kBadPayload;
    if (ok(m.status)) {
        const FrameError e = r.value(m.value);
        if (e != FrameError::kNone) return e;
    }
    return r.done() ? FrameError::kNone : FrameError::kBadPayload;
}

void encode(const WriteRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.descriptor(m.descriptor);
    w.value(m.value);
}
FrameError decode(std::span<const std::uint8_t> p, WriteRequest& m) {
    ByteReader r(p);
    if (!r.descriptor(m.descriptor)) return FrameError::kBadPayload;
    const FrameError e = r.value(m.value);
    if (e != FrameError::kNone) return e;
    return r.done() ? FrameError::kNone : FrameError::kBadPayload;
}

void encode(const WriteReply& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    w.u32(m.handle);
}
FrameError decode(std::span<const std::uint8_t> p, WriteReply& m) {
    ByteReader r(p);
    std::uint32_t code;
    if (!r.u32(code) || !r.u32(m.handle) || !r.done()) return FrameError::kBadPayload;
    if (!status_from_code(code, m.status)) return FrameError::kBadPayload;
    return FrameError::kNone;
}

void encode(const ErrorReply& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    w.u8(static_cast<std::uint8_t>(m.reason));
}
FrameError decode(std::span<const std::uint8_t> p, ErrorReply& m) {
    ByteReader r(p);
    std::uint32_t code;
    std::uint8_t reason;
    if (!r.u32(code) || !r.u8(reason) || !r.done()) return FrameError::kBadPayload;
    if (!status_from_code(code, m.status)) return FrameError::kBadPayload;
    if (reason > static_cast<std::uint8_t>(FrameError::kNotFinite)) return FrameError::kBadPayload;
    m.reason = static_cast<FrameError>(reason);
    return FrameError::kNone;
}

namespace {
constexpr bool printable(std::uint8_t c) noexcept {
    return c >= 0x20 && c < 0x7F;
}
}  // namespace

void encode(const Notice& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    const std::size_t n = std::min(m.text.size(), kMaxNoticeText);
    w.u16(static_cast<std::uint16_t>(n));
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<std::uint8_t>(m.text[i]);
        w.u8(printable(c) ? c : static_cast<std::uint8_t>('?'));
    }
}
FrameError decode(std::span<const std::uint8_t> p, Notice& m) {
    ByteReader r(p);
    std::uint32_t code;
    std::uint16_t n;
    if (!r.u32(code) || !r.u16(n) || n > kMaxNoticeText || r.remaining() != n)
        return FrameError::kBadPayload;
    if (!status_from_code(code, m.status)) return FrameError::kBadPayload;
    const auto text = p.subspan(p.size() - n);
    if (!std::all_of(text.begin(), text.end(), printable)) return FrameError::kBadPayload;
    m.text.assign(text.begin(), text.end());
    return FrameError::kNone;
}

// ---- Motion payloads

namespace {

FrameError finite(ByteReader& r, double& v) {
    if (!r.f64(v)) return FrameError::kBadPayload;
    return std::isfinite(v) ? FrameError::kNone : FrameError::kNotFinite;
}

template <std::size_t N>
FrameError finite(ByteReader& r, std::array<double, N>& v) {
    for (double& d : v)
        if (const FrameError e = finite(r, d); e != FrameError::kNone) return e;
    return FrameError::kNone;
}

template <std::size_t N>
void put(ByteWriter& w, const std::array<double, N>& v) {
    for (double d : v) w.f64(d);
}

FrameError status_of(ByteReader& r, Status& s) {
    std::uint32_t code;
    if (!r.u32(code) || !status_from_code(code, s)) return FrameError::kBadPayload;
    return FrameError::kNone;
}

bool flag(ByteReader& r, bool& b) {
    std::uint8_t v;
    if (!r.u8(v) || v > 1) return false;
    b = v == 1;
    return true;
}

// Runs the checks in order; the first failure wins.
#define OBJIF_TRY(expr)                                 \
    do {                                                \
        if (const FrameError e_ = (expr); e_ != FrameError::kNone) return e_; \
    } while (0)
#define OBJIF_NEED(cond) \
    do {                 \
        if (!(cond)) return FrameError::kBadPayload; \
    } while (0)

}  // namespace

void encode(const SpoolRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u8(m.kind);
    w.u8(m.axes);
    w.u8(m.arc_axes[0]);
    w.u8(m.arc_axes[1]);
    w.u32(m.tag);
    w.f64(m.feed);
    put(w, m.target);
    put(w, m.center);
}
FrameError decode(std::span<const std::uint8_t> p, SpoolRequest& m) {
    ByteReader r(p);
    OBJIF_NEED(r.u8(m.kind) && r.u8(m.axes) && r.u8(m.arc_axes[0]) && r.u8(m.arc_axes[1]) &&
               r.u32(m.tag));
    OBJIF_TRY(finite(r, m.feed));
    OBJIF_TRY(finite(r, m.target));
    OBJIF_TRY(finite(r, m.center));
    OBJIF_NEED(r.done());
    return FrameError::kNone;
}

void encode(const DirectRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u16(m.code);
    w.u8(m.axes);
    w.f64(m.feed);
    put(w, m.target);
}
FrameError decode(std::span<const std::uint8_t> p, DirectRequest& m) {
    ByteReader r(p);
    OBJIF_NEED(r.u16(m.code) && r.u8(m.axes));
    OBJIF_TRY(finite(r, m.feed));
    OBJIF_TRY(finite(r, m.target));
    OBJIF_NEED(r.done());
    return FrameError::kNone;
}

void encode(const SsfRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u8(m.axes);
    w.i32(m.command);
}
FrameError decode(std::span<const std::uint8_t> p, SsfRequest& m) {
    ByteReader r(p);
    OBJIF_NEED(r.u8(m.axes) && r.i32(m.command) && r.done());
    return FrameError::kNone;
}

void encode(const MotionReply& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    w.i32(m.group);
    w.i32(m.errors);
    w.u32(m.tag);
    const std::size_t n = m.message.size() < kMaxMotionMessage ? m.message.size() : kMaxMotionMessage;
    w.u16(static_cast<std::uint16_t>(n));
    out.insert(out.end(), m.message.begin(), m.message.begin() + static_cast<std::ptrdiff_t>(n));
}
FrameError decode(std::span<const std::uint8_t> p, MotionReply& m) {
    ByteReader r(p);
    OBJIF_TRY(status_of(r, m.status));
    std::uint16_t n;
    OBJIF_NEED(r.i32(m.group) && r.i32(m.errors) && r.u32(m.tag) && r.u16(n));
    OBJIF_NEED(n <= kMaxMotionMessage && r.remaining() == n);
    const auto text = p.subspan(p.size() - n);
    m.message.assign(text.begin(), text.end());
    return FrameError::kNone;
}

void encode(const ClockRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u8(static_cast<std::uint8_t>(m.mode));
    w.u64(m.cycles);
}
FrameError decode(std::span<const std::uint8_t> p, ClockRequest& m) {
    ByteReader r(p);
    std::uint8_t mode;
    OBJIF_NEED(r.u8(mode) && r.u64(m.cycles) && r.done());
    OBJIF_NEED(mode <= static_cast<std::uint8_t>(ClockMode::kTraceOff));
    m.mode = static_cast<ClockMode>(mode);
    return FrameError::kNone;
}

void encode(const ClockReply& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    w.u64(m.ran);
    w.u64(m.now);
    w.u8(m.flags);
    w.u32(m.fill);
    w.u32(m.capacity);
    w.i32(m.compensating_group);
    w.u64(m.trace_pending);
    w.u64(m.trace_lost);
    w.u64(m.segments_pending);
    w.u64(m.segments_lost);
    put(w, m.position);
}
FrameError decode(std::span<const std::uint8_t> p, ClockReply& m) {
    ByteReader r(p);
    OBJIF_TRY(status_of(r, m.status));
    OBJIF_NEED(r.u64(m.ran) && r.u64(m.now) && r.u8(m.flags) && r.u32(m.fill) &&
               r.u32(m.capacity) && r.i32(m.compensating_group) && r.u64(m.trace_pending) &&
               r.u64(m.trace_lost) && r.u64(m.segments_pending) && r.u64(m.segments_lost));
    OBJIF_NEED((m.flags & ~kClockFlagMask) == 0);
    OBJIF_TRY(finite(r, m.position));
    OBJIF_NEED(r.done());
    return FrameError::kNone;
}

void encode(const TraceRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u8(static_cast<std::uint8_t>(m.what));
    w.u32(m.max);
}
FrameError decode(std::span<const std::uint8_t> p, TraceRequest& m) {
    ByteReader r(p);
    std::uint8_t what;
    OBJIF_NEED(r.u8(what) && r.u32(m.max) && r.done());
    OBJIF_NEED(what <= static_cast<std::uint8_t>(TraceKind::kSegments));
    m.what = static_cast<TraceKind>(what);
    return FrameError::kNone;
}

namespace {
// The segment's flags byte (docs/motion.md section 9).
constexpr std::uint8_t kSegmentInterrupted = 0x01;
constexpr std::uint8_t kSegmentTraverse = 0x02;

void put(ByteWriter& w, const WireSegment& s) {
    w.u32(s.tag);
    w.u8(s.kind);
    w.u8(s.role);
    w.u8(s.ccw ? 1 : 0);
    w.u8(static_cast<std::uint8_t>((s.interrupted ? kSegmentInterrupted : 0) |
                                   (s.traverse ? kSegmentTraverse : 0)));
    w.u8(s.plane_axes[0]);
    w.u8(s.plane_axes[1]);
    w.i32(s.plane);
    put(w, s.start);
    put(w, s.end);
    put(w, s.center);
    w.f64(s.feed);
    w.u64(s.start_cycle);
    w.u64(s.end_cycle);
    put(w, s.length_start);
    put(w, s.length_end);
}
FrameError take(ByteReader& r, WireSegment& s) {
    std::uint8_t flags = 0;
    OBJIF_NEED(r.u32(s.tag) && r.u8(s.kind) && r.u8(s.role) && flag(r, s.ccw) && r.u8(flags) &&
               r.u8(s.plane_axes[0]) && r.u8(s.plane_axes[1]) && r.i32(s.plane));
    OBJIF_NEED(s.kind <= 1 && s.role <= 5);
    OBJIF_NEED((flags & ~(kSegmentInterrupted | kSegmentTraverse)) == 0);
    s.interrupted = (flags & kSegmentInterrupted) != 0;
    s.traverse = (flags & kSegmentTraverse) != 0;
    OBJIF_TRY(finite(r, s.start));
    OBJIF_TRY(finite(r, s.end));
    OBJIF_TRY(finite(r, s.center));
    OBJIF_TRY(finite(r, s.feed));
    OBJIF_NEED(r.u64(s.start_cycle) && r.u64(s.end_cycle));
    OBJIF_TRY(finite(r, s.length_start));
    OBJIF_TRY(finite(r, s.length_end));
    return FrameError::kNone;
}
}  // namespace

void encode(const TraceReply& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    w.u8(static_cast<std::uint8_t>(m.what));
    if (m.what == TraceKind::kSamples) {
        const std::size_t n = std::min(m.samples.size(), kMaxSamplesPerReply);
        w.u32(static_cast<std::uint32_t>(n));
        for (std::size_t i = 0; i < n; ++i) {
            w.u64(m.samples[i].cycle);
            put(w, m.samples[i].position);
        }
    } else {
        const std::size_t n = std::min(m.segments.size(), kMaxSegmentsPerReply);
        w.u32(static_cast<std::uint32_t>(n));
        for (std::size_t i = 0; i < n; ++i) put(w, m.segments[i]);
    }
}
FrameError decode(std::span<const std::uint8_t> p, TraceReply& m) {
    ByteReader r(p);
    OBJIF_TRY(status_of(r, m.status));
    std::uint8_t what;
    std::uint32_t count;
    OBJIF_NEED(r.u8(what) && r.u32(count));
    OBJIF_NEED(what <= static_cast<std::uint8_t>(TraceKind::kSegments));
    m.what = static_cast<TraceKind>(what);
    m.samples.clear();
    m.segments.clear();
    if (m.what == TraceKind::kSamples) {
        OBJIF_NEED(count <= kMaxSamplesPerReply && r.remaining() == count * kWireSampleSize);
        m.samples.resize(count);
        for (WireSample& s : m.samples) {
            OBJIF_NEED(r.u64(s.cycle));
            OBJIF_TRY(finite(r, s.position));
        }
    } else {
        OBJIF_NEED(count <= kMaxSegmentsPerReply && r.remaining() == count * kWireSegmentSize);
        m.segments.resize(count);
        for (WireSegment& s : m.segments) OBJIF_TRY(take(r, s));
    }
    return FrameError::kNone;
}

void encode(const ClaimRequest& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u8(static_cast<std::uint8_t>(m.action));
}
FrameError decode(std::span<const std::uint8_t> p, ClaimRequest& m) {
    ByteReader r(p);
    std::uint8_t action;
    OBJIF_NEED(r.u8(action) && r.done());
    OBJIF_NEED(action <= static_cast<std::uint8_t>(ClaimAction::kQuery));
    m.action = static_cast<ClaimAction>(action);
    return FrameError::kNone;
}

void encode(const ClaimReply& m, std::vector<std::uint8_t>& out) {
    ByteWriter w(out);
    w.u32(status_code(m.status));
    w.u8(m.held ? 1 : 0);
    w.u8(m.yours ? 1 : 0);
    w.i32(m.pid);
    w.u64(m.since_ms);
    const std::size_t n = std::min(m.name.size(), kMaxHolderName);
    w.u8(static_cast<std::uint8_t>(n));
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<std::uint8_t>(m.name[i]);
        w.u8(printable(c) ? c : static_cast<std::uint8_t>('?'));
    }
}
FrameError decode(std::span<const std::uint8_t> p, ClaimReply& m) {
    ByteReader r(p);
    OBJIF_TRY(status_of(r, m.status));
    std::uint8_t n;
    OBJIF_NEED(flag(r, m.held) && flag(r, m.yours) && r.i32(m.pid) && r.u64(m.since_ms) &&
               r.u8(n));
    OBJIF_NEED(n <= kMaxHolderName && r.remaining() == n && (m.held || !m.yours) && m.pid >= 0);
    const auto text = p.subspan(p.size() - n);
    OBJIF_NEED(std::all_of(text.begin(), text.end(), printable));
    m.name.assign(text.begin(), text.end());
    return FrameError::kNone;
}

std::string claim_holder_text(const ClaimReply& reply) {
    std::string out;
    if (reply.pid != 0) {
        out = "pid " + std::to_string(reply.pid);
        if (!reply.name.empty()) out += " (" + reply.name + ")";
    } else {
        out = reply.name.empty() ? "another host" : reply.name;
    }
    if (reply.since_ms != 0) {
        const auto seconds = static_cast<std::time_t>(reply.since_ms / 1000);
        std::tm utc{};
        char when[32];
        if (::gmtime_r(&seconds, &utc) != nullptr &&
            std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", &utc) != 0)
            out += std::string(" since ") + when;
    }
    return out;
}

bool guarded_by_motion_claim(std::uint16_t opcode, std::span<const std::uint8_t> payload) noexcept {
    switch (static_cast<Opcode>(opcode)) {
        case Opcode::kObjectWrite:    // every writable object acts on the motion or its record
        case Opcode::kSpoolProfile:
        case Opcode::kDirectCommand:
        case Opcode::kSsfCommand:
        case Opcode::kReadTrace:      // takes the samples and segments the holder's run records
            return true;
        case Opcode::kClock:
            // The mode is the payload's first byte; a clock query changes nothing.
            return payload.empty() || payload[0] != static_cast<std::uint8_t>(ClockMode::kQuery);
        default:  // object reads, the claim itself, replies and opcodes nobody serves
            return false;
    }
}

#undef OBJIF_TRY
#undef OBJIF_NEED

FrameError decode_status(std::span<const std::uint8_t> p, Status& s) {
    ByteReader r(p);
    std::uint32_t code;
    if (!r.u32(code) || !status_from_code(code, s)) return FrameError::kBadPayload;
    return FrameError::kNone;
}

}  // namespace objif
