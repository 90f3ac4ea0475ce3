// SPDX-License-Identifier: MIT
// Wire frames (docs/design.md section 2, design): the same frames travel over every
// transport that leaves the process (daemon socket, dual-port RAM mailbox, USB bulk
// endpoints); the in-process emulator is called directly.
//
//   offset size field
//   0      4    magic   0x49435041 ("APCI" in little-endian byte order)
//   4      2    version 1
//   6      2    opcode  (replies: request opcode | 0x8000)
//   8      4    sequence (echoed in the reply)
//   12     4    payload length (<= kMaxPayload)
//   16     n    payload
//   16+n   4    CRC-32 (IEEE, zlib) over bytes 0..16+n-1
// All integers little-endian. docs/wire-frame.md is the spec page.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "objif/descriptor.h"
#include "objif/status.h"
#include "objif/value.h"

namespace objif {

inline constexpr std::uint32_t kFrameMagic = 0x49435041;
// 2 since 0.2.0: the ReadTrace segment record carries the tool length at start and end (358
// bytes, 230 in version 1). Each side refuses the other version at the first frame (a stream
// drops the connection) rather than misreading a record later.
inline constexpr std::uint16_t kFrameVersion = 2;
inline constexpr std::size_t kFrameHeaderSize = 16;
inline constexpr std::size_t kFrameCrcSize = 4;
inline constexpr std::size_t kFrameOverhead = kFrameHeaderSize + kFrameCrcSize;
inline constexpr std::uint32_t kMaxPayload = 64 * 1024;
inline constexpr std::uint16_t kReplyFlag = 0x8000;

enum class Opcode : std::uint16_t {
    kObjectRead = 0x0001,
    kObjectWrite = 0x0002,
    kSpoolProfile = 0x0003,
    kDirectCommand = 0x0004,
    kSsfCommand = 0x0005,
    kClock = 0x0006,      // step / run the interpolation clock
    kReadTrace = 0x0007,  // per-cycle axis samples
    kMotionClaim = 0x0008,  // claim, release or ask who holds the board's motion (ClaimRequest)
    kNotice = 0x7FFE,     // sent by the daemon on its own (as 0xFFFE, sequence 0): greeting,
                          // refusal, or why it closes the connection (NoticeFrame)
    kError = 0x7FFF,      // reply only: the request could not be decoded
};
bool opcode_known(std::uint16_t op) noexcept;  // a request opcode we define
std::string_view opcode_name(std::uint16_t op) noexcept;

// Why a byte sequence is not a valid frame. Each is named for logs and errors.
enum class FrameError : std::uint8_t {
    kNone = 0,
    kShort,          // fewer bytes than the header or than the header announces
    kBadMagic,
    kBadVersion,
    kBadLength,      // payload length above kMaxPayload
    kBadCrc,
    kUnknownOpcode,
    kBadPayload,     // payload size or content does not fit the opcode
    kBadValueTag,    // value tag is neither int32 nor double
    kNotFinite,      // a double value is NaN or infinite
};
std::string_view frame_error_name(FrameError e) noexcept;
// The status a reply carries for a frame error.
Status frame_error_status(FrameError e) noexcept;

struct Frame {
    std::uint16_t opcode = 0;
    std::uint32_t sequence = 0;
    std::vector<std::uint8_t> payload;
};

// Appends the encoded frame to `out`.
void encode_frame(std::uint16_t opcode, std::uint32_t sequence,
                  std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out);

// Decodes one frame from the front of `bytes`.
//   kOk: `out` holds the frame, `consumed` its size.
//   kShort with `need_more` = true: the bytes are a valid prefix; read more.
//   kBadCrc, kUnknownOpcode: the frame's boundary is known: `consumed` is its
//   size and `out.opcode`/`out.sequence` are filled, so a stream transport
//   answers kError and goes on with the next frame.
//   kBadMagic, kBadVersion, kBadLength: garbage, `consumed` is 0: a stream
//   transport drops the connection; a datagram transport answers kError.
// Header fields are checked in order: magic, version, length, then CRC, then opcode.
FrameError decode_frame(std::span<const std::uint8_t> bytes, Frame& out, std::size_t& consumed,
                        bool& need_more);

// ---- Payload codecs. Each decode checks size and content and never throws.

// Little-endian byte writer/reader shared by the payload codecs.
class ByteWriter {
public:
    explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
    void u8(std::uint8_t v) { out_.push_back(v); }
    void u16(std::uint16_t v);
    void u32(std::uint32_t v);
    void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
    void u64(std::uint64_t v);
    void f64(double v);
    void value(const Value& v);  // tag byte + 4 (int32) or 8 (double) bytes
    void address(const Address& a);
    void descriptor(const Descriptor& d);

private:
    std::vector<std::uint8_t>& out_;
};

class ByteReader {
public:
    explicit ByteReader(std::span<const std::uint8_t> in) : in_(in) {}
    bool u8(std::uint8_t& v);
    bool u16(std::uint16_t& v);
    bool u32(std::uint32_t& v);
    bool i32(std::int32_t& v);
    bool u64(std::uint64_t& v);
    bool f64(double& v);
    // Reads tag + value; tag errors and non-finite doubles are reported.
    FrameError value(Value& v);
    bool address(Address& a);
    bool descriptor(Descriptor& d);
    std::size_t remaining() const noexcept { return in_.size() - pos_; }
    bool done() const noexcept { return pos_ == in_.size(); }

private:
    std::span<const std::uint8_t> in_;
    std::size_t pos_ = 0;
};

struct ReadRequest {
    Descriptor descriptor;
    ValueType want = ValueType::kInt32;
};
struct ReadReply {
    Status status = Status::kOk;
    Handle handle = kNoHandle;
    Value value;  // present on the wire only when status is kOk
};
struct WriteRequest {
    Descriptor descriptor;
    Value value;
};
struct WriteReply {
    Status status = Status::kOk;
    Handle handle = kNoHandle;
};
struct ErrorReply {
    Status status = Status::kBadFrame;
    FrameError reason = FrameError::kNone;
};

// The frame the daemon sends on its own on a stream connection (opcode
// kNotice | kReplyFlag, sequence 0; docs/wire-frame.md "Notices"): at once
// after accepting it, status Ok and the text kDaemonGreeting (a client opens
// the link only once it has read it); a refused connection, or one the daemon
// closes (idle, shutting down), gets a status other than Ok and the reason,
// then the daemon closes it. The text is printable ASCII, at most
// kMaxNoticeText bytes.
inline constexpr std::size_t kMaxNoticeText = 256;
inline constexpr std::string_view kDaemonGreeting = "rwmos-emu";
struct Notice {
    Status status = Status::kOk;
    std::string text;
};

void encode(const ReadRequest& m, std::vector<std::uint8_t>& out);
void encode(const ReadReply& m, std::vector<std::uint8_t>& out);
void encode(const WriteRequest& m, std::vector<std::uint8_t>& out);
void encode(const WriteReply& m, std::vector<std::uint8_t>& out);
void encode(const ErrorReply& m, std::vector<std::uint8_t>& out);
FrameError decode(std::span<const std::uint8_t> p, ReadRequest& m);
FrameError decode(std::span<const std::uint8_t> p, ReadReply& m);
FrameError decode(std::span<const std::uint8_t> p, WriteRequest& m);
FrameError decode(std::span<const std::uint8_t> p, WriteReply& m);
FrameError decode(std::span<const std::uint8_t> p, ErrorReply& m);
// Text longer than kMaxNoticeText is cut; bytes that are not printable ASCII
// become '?'. decode refuses both.
void encode(const Notice& m, std::vector<std::uint8_t>& out);
FrameError decode(std::span<const std::uint8_t> p, Notice& m);

// ---- Motion payloads (docs/motion.md section 9, "Wire payloads"). Plain wire structs:
// the board's motion types (rwmos/motion/types.h) map onto them one to one.
// Every double must be finite (kNotFinite otherwise); enumerations the codec
// knows (clock mode, trace kind, segment kind/role) are checked here, values
// with a meaning on the board (profile kind, direct code, axis numbers,
// ranges) are checked by the board, which answers with a status.

inline constexpr std::size_t kWireAxisCount = 8;
using WireAxes = std::array<double, kWireAxisCount>;

struct SpoolRequest {
    std::uint8_t kind = 1;  // 0 G00, 1 G01, 2 G02, 3 G03
    std::uint8_t axes = 0;  // bit i: axis i named
    std::array<std::uint8_t, 2> arc_axes{0, 1};
    std::uint32_t tag = 0;  // NC block number
    double feed = 0.0;      // units per minute
    WireAxes target{};
    std::array<double, 2> center{};
};
struct DirectRequest {
    std::uint16_t code = 0;  // 1 JA, 2 JS
    std::uint8_t axes = 0;
    double feed = 0.0;
    WireAxes target{};
};
struct SsfRequest {
    std::uint8_t axes = 0;
    std::int32_t command = 0;
};
// Reply to SpoolProfile, DirectCommand and SsfCommand.
inline constexpr std::size_t kMaxMotionMessage = 1024;
struct MotionReply {
    Status status = Status::kOk;
    std::int32_t group = 0;   // TC group whose ERROR got `errors` (0: none)
    std::int32_t errors = 0;  // Table 4 bits this request set
    std::uint32_t tag = 0;    // block at fault
    std::string message;      // why, at most kMaxMotionMessage bytes
};

enum class ClockMode : std::uint8_t {
    kStep = 0,          // advance exactly `cycles` cycles
    kRunUntilIdle = 1,  // advance until nothing moves, at most `cycles` cycles
    kQuery = 2,         // only the status
    kTraceOn = 3,       // per-cycle samples on, ring of `cycles` samples
    kTraceOff = 4,      // per-cycle samples off
};
struct ClockRequest {
    ClockMode mode = ClockMode::kQuery;
    std::uint64_t cycles = 0;
};
// The most cycles one Step or RunUntilIdle request may advance (2^20, about
// 17 minutes at the default 1 ms cycle); more is answered ValueTooHigh and
// nothing runs. The board serves requests one at a time, and with the trace
// on each cycle is computed (30 to 45 ns), so this bounds how long one
// request holds the board for every other client (about 50 ms). libapci's apci_step and
// apci_run_until_idle take any count and send as many requests as it takes.
inline constexpr std::uint64_t kMaxClockCycles = std::uint64_t{1} << 20;
// Flag bits of ClockReply::flags.
inline constexpr std::uint8_t kClockIdle = 0x01;
inline constexpr std::uint8_t kClockHeld = 0x02;         // spooler holds after a TC error
inline constexpr std::uint8_t kClockProfileHeld = 0x04;  // ProfMarked of the compensating group
inline constexpr std::uint8_t kClockTracing = 0x08;
inline constexpr std::uint8_t kClockFlagMask = 0x0F;
struct ClockReply {
    Status status = Status::kOk;
    std::uint64_t ran = 0;  // cycles this request advanced
    std::uint64_t now = 0;  // cycles since power-on
    std::uint8_t flags = 0;
    std::uint32_t fill = 0;
    std::uint32_t capacity = 0;
    std::int32_t compensating_group = 0;
    std::uint64_t trace_pending = 0;
    std::uint64_t trace_lost = 0;
    std::uint64_t segments_pending = 0;
    std::uint64_t segments_lost = 0;
    WireAxes position{};
};

enum class TraceKind : std::uint8_t { kSamples = 0, kSegments = 1 };
struct TraceRequest {
    TraceKind what = TraceKind::kSamples;
    std::uint32_t max = 0;  // the most items wanted; the reply may carry fewer
};
struct WireSample {
    std::uint64_t cycle = 0;
    WireAxes position{};
};
struct WireSegment {
    std::uint32_t tag = 0;
    std::uint8_t kind = 0;  // 0 line, 1 arc
    std::uint8_t role = 0;  // 0 contour, 1 transition, 2 approach, 3 departure, 4 uncompensated, 5 rapid
    bool ccw = false;
    bool interrupted = false;  // flags bit 0x01 on the wire
    bool traverse = false;     // flags bit 0x02: from a traverse profile (a compensated G00)
    std::array<std::uint8_t, 2> plane_axes{0, 1};
    std::int32_t plane = 0;
    WireAxes start{};
    WireAxes end{};
    WireAxes center{};
    double feed = 0.0;
    std::uint64_t start_cycle = 0;
    std::uint64_t end_cycle = 0;
    // The tool length compensation in start and in end, per axis: the tool centre point is the
    // position less these.
    WireAxes length_start{};
    WireAxes length_end{};
};
inline constexpr std::size_t kWireSampleSize = 8 + 8 * kWireAxisCount;
inline constexpr std::size_t kWireSegmentSize = 4 + 4 + 2 + 4 + kWireAxisCount * 3 * 8 + 8 + 16 +
                                                kWireAxisCount * 2 * 8;
inline constexpr std::size_t kTraceReplyHeader = 4 + 1 + 4;
// The most items one ReadTrace reply carries (the payload limit).
inline constexpr std::size_t kMaxSamplesPerReply = (kMaxPayload - kTraceReplyHeader) / kWireSampleSize;
inline constexpr std::size_t kMaxSegmentsPerReply = (kMaxPayload - kTraceReplyHeader) / kWireSegmentSize;
struct TraceReply {
    Status status = Status::kOk;
    TraceKind what = TraceKind::kSamples;
    std::vector<WireSample> samples;    // what == kSamples
    std::vector<WireSegment> segments;  // what == kSegments
};

void encode(const SpoolRequest& m, std::vector<std::uint8_t>& out);
void encode(const DirectRequest& m, std::vector<std::uint8_t>& out);
void encode(const SsfRequest& m, std::vector<std::uint8_t>& out);
void encode(const MotionReply& m, std::vector<std::uint8_t>& out);
void encode(const ClockRequest& m, std::vector<std::uint8_t>& out);
void encode(const ClockReply& m, std::vector<std::uint8_t>& out);
void encode(const TraceRequest& m, std::vector<std::uint8_t>& out);
void encode(const TraceReply& m, std::vector<std::uint8_t>& out);
FrameError decode(std::span<const std::uint8_t> p, SpoolRequest& m);
FrameError decode(std::span<const std::uint8_t> p, DirectRequest& m);
FrameError decode(std::span<const std::uint8_t> p, SsfRequest& m);
FrameError decode(std::span<const std::uint8_t> p, MotionReply& m);
FrameError decode(std::span<const std::uint8_t> p, ClockRequest& m);
FrameError decode(std::span<const std::uint8_t> p, ClockReply& m);
FrameError decode(std::span<const std::uint8_t> p, TraceRequest& m);
FrameError decode(std::span<const std::uint8_t> p, TraceReply& m);

// ---- The motion claim (docs/motion-claim.md): one host at a time holds the board's motion;
// while one does, the board refuses the others' requests that start or change motion
// (MotionClaimed). The board knows its hosts by their link (a socket connection, a mailbox
// host's pid) and names the holder to the others.
enum class ClaimAction : std::uint8_t {
    kClaim = 0,    // take the motion for this host; MotionClaimed while another holds it
    kRelease = 1,  // give it back; WrongDeviceState when this host does not hold it
    kQuery = 2,    // who holds it, changing nothing
};
struct ClaimRequest {
    ClaimAction action = ClaimAction::kQuery;
};
// The longest holder name on the wire: a Linux command name (comm) is at most 15 bytes.
inline constexpr std::size_t kMaxHolderName = 15;
struct ClaimReply {
    Status status = Status::kOk;
    bool held = false;         // someone holds the motion (after the action)
    bool yours = false;        // and it is the host that asked
    std::int32_t pid = 0;      // the holder's process id, 0 when the board does not know it
    std::uint64_t since_ms = 0;  // when it claimed, milliseconds since 1970-01-01 UTC
    std::string name;          // the holder's command name ("apcictl"); printable ASCII
};

// "pid 4242 (apcictl) since 2024-05-01 12:00:00 UTC" for a reply whose `held` is set (the
// name and the pid left out where the board does not know them): the one way the board side
// and libapci name a holder.
std::string claim_holder_text(const ClaimReply& reply);

void encode(const ClaimRequest& m, std::vector<std::uint8_t>& out);
void encode(const ClaimReply& m, std::vector<std::uint8_t>& out);
FrameError decode(std::span<const std::uint8_t> p, ClaimRequest& m);
FrameError decode(std::span<const std::uint8_t> p, ClaimReply& m);

// Whether a request starts or changes the board's motion, or takes from what the holder's
// run records, and is therefore refused to a host that does not hold a claim another host
// holds: object writes, profiles, direct and SSF commands, clock requests other than a query,
// trace reads (docs/motion-claim.md, "What the claim guards"). Object reads, clock queries and
// MotionClaim requests are answered to everyone.
bool guarded_by_motion_claim(std::uint16_t opcode, std::span<const std::uint8_t> payload) noexcept;

// A reply's status word: the first 4 payload bytes of every reply.
FrameError decode_status(std::span<const std::uint8_t> p, Status& s);

}  // namespace objif
