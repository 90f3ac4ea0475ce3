// SPDX-License-Identifier: MIT
#include "objif/frame.h"

#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstring>

namespace objif {

static_assert(std::endian::native == std::endian::little,
              "the codec copies little-endian integers directly");

bool opcode_known(std::uint16_t op) noexcept {
    return op >= static_cast<std::uint16_t>(Opcode::kObjectRead) &&
           op <= static_cast<std::uint16_t>(Opcode::kReadTrace);
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
        case Opcode::kError: return "Error";
    }
    return "Unknown";
}

std::string_view frame_error_name(FrameError e) noexcept {
    switch (e) {
        case FrameError::kNone: return "none";
        case FrameError::kShort: return "short frame";
        case FrameError::kBadMagic: return "bad magic";
        case FrameError::kBadVersion: return "bad version";
        case FrameError::kBadLength: return "bad payload length";
        case FrameError::kBadCrc: return "bad CRC";
        case FrameError::kUnknownOpcode: return "unknown opcode";
        case FrameError::kBadPayload: return "bad payload for opcode";
        case FrameError::kBadValueTag: return "bad value tag";
        case FrameError::kNotFinite: return "value is NaN or infinite";
    }
    return "unknown frame error";
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
template <class T>
T load(const std::uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
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
    if (n < 4) {
        // A prefix of the magic is still a valid prefix.
        std::uint8_t magic[4];
        std::memcpy(magic, &kFrameMagic, 4);
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
    if (!opcode_known(base) && base != static_cast<std::uint16_t>(Opcode::kError))
        return FrameError::kUnknownOpcode;
    out.payload.assign(p + kFrameHeaderSize, p + kFrameHeaderSize + length);
    return FrameError::kNone;
}

// ---- ByteWriter / ByteReader

void ByteWriter::u16(std::uint16_t v) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out_.insert(out_.end(), b, b + sizeof v);
}
void ByteWriter::u32(std::uint32_t v) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out_.insert(out_.end(), b, b + sizeof v);
}
void ByteWriter::u64(std::uint64_t v) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out_.insert(out_.end(), b, b + sizeof v);
}
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
    std::memcpy(&v, in.data() + pos, sizeof(T));
    pos += sizeof(T);
    return true;
}
bool ByteReader::u8(std::uint8_t& v) { return take(in_, pos_, v); }
bool ByteReader::u16(std::uint16_t& v) { return take(in_, pos_, v); }
bool ByteReader::u32(std::uint32_t& v) { return take(in_, pos_, v); }
bool ByteReader::i32(std::int32_t& v) { return take(in_, pos_, v); }
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

FrameError decode_status(std::span<const std::uint8_t> p, Status& s) {
    ByteReader r(p);
    std::uint32_t code;
    if (!r.u32(code) || !status_from_code(code, s)) return FrameError::kBadPayload;
    return FrameError::kNone;
}

}  // namespace objif
