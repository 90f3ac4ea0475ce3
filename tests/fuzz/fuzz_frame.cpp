// SPDX-License-Identifier: MIT
// Fuzz target: the wire frame decoder (objif/frame.h) and the emulator side
// that serves it (rwmos/frame_server.h). The input is taken three ways:
//   1. as a byte stream, frame after frame, the way a stream transport (the
//      daemon socket) reads it: every decode result is checked against the
//      documented contract, and every well-formed frame re-encodes to the
//      same bytes;
//   2. each well-formed frame's payload through every payload codec: a payload
//      that decodes re-encodes to the same bytes;
//   3. as one datagram (mailbox, USB transfer) served by a FrameServer: the
//      reply is exactly one well-formed frame echoing the sequence, and a
//      rejected request changes nothing a client can observe.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "board_snapshot.h"
#include "fuzz_check.h"
#include "objif/frame.h"
#include "rwmos/board.h"
#include "rwmos/frame_server.h"

namespace {

using objif::FrameError;
using Bytes = std::span<const std::uint8_t>;

// Every payload codec of objif/frame.h is listed in check_payload_codecs: a
// new opcode's codecs go there too.
// A payload that decodes as M must re-encode to exactly the same bytes: the
// codecs have one encoding per message, so nothing is silently dropped.
template <class M>
void check_payload_round_trip(Bytes payload) {
    M message;
    if (objif::decode(payload, message) != FrameError::kNone) return;
    std::vector<std::uint8_t> again;
    objif::encode(message, again);
    FUZZ_CHECK(std::equal(again.begin(), again.end(), payload.begin(), payload.end()),
               "a decoded payload re-encodes to the same bytes");
}

void check_payload_codecs(Bytes payload) {
    check_payload_round_trip<objif::ReadRequest>(payload);
    check_payload_round_trip<objif::ReadReply>(payload);
    check_payload_round_trip<objif::WriteRequest>(payload);
    check_payload_round_trip<objif::WriteReply>(payload);
    check_payload_round_trip<objif::ErrorReply>(payload);
    check_payload_round_trip<objif::SpoolRequest>(payload);
    check_payload_round_trip<objif::DirectRequest>(payload);
    check_payload_round_trip<objif::SsfRequest>(payload);
    check_payload_round_trip<objif::MotionReply>(payload);
    check_payload_round_trip<objif::ClockRequest>(payload);
    check_payload_round_trip<objif::ClockReply>(payload);
    check_payload_round_trip<objif::TraceRequest>(payload);
    check_payload_round_trip<objif::TraceReply>(payload);
    objif::Status status;
    (void)objif::decode_status(payload, status);
}

// Reads the input as a stream transport does; returns when the rest is a
// prefix waiting for more bytes, or garbage that drops the connection.
void decode_as_stream(Bytes bytes) {
    while (!bytes.empty()) {
        objif::Frame frame;
        std::size_t consumed = 0;
        bool need_more = false;
        const FrameError e = objif::decode_frame(bytes, frame, consumed, need_more);
        FUZZ_CHECK(consumed <= bytes.size(), "a frame never claims more bytes than given");
        FUZZ_CHECK(!need_more || e == FrameError::kShort, "need_more only with kShort");
        switch (e) {
            case FrameError::kNone: {
                FUZZ_CHECK(consumed == objif::kFrameOverhead + frame.payload.size(),
                           "a frame's size is header + payload + CRC");
                std::vector<std::uint8_t> again;
                objif::encode_frame(frame.opcode, frame.sequence, frame.payload, again);
                FUZZ_CHECK(std::equal(again.begin(), again.end(), bytes.begin(), bytes.begin() + consumed),
                           "a decoded frame re-encodes to the same bytes");
                check_payload_codecs(frame.payload);
                break;
            }
            case FrameError::kBadCrc:
            case FrameError::kUnknownOpcode:
                FUZZ_CHECK(consumed >= objif::kFrameOverhead, "bad CRC/opcode: the boundary is known");
                break;
            case FrameError::kShort:
                FUZZ_CHECK(need_more && consumed == 0, "a short frame asks for more and consumes nothing");
                return;
            default:
                FUZZ_CHECK(consumed == 0, "garbage consumes nothing (the connection is dropped)");
                return;
        }
        bytes = bytes.subspan(consumed);
    }
}

// What a fresh board shows: every board a request is served on starts so.
const std::vector<fuzz::ObservedObject>& fresh_board() {
    static const std::vector<fuzz::ObservedObject> seen = [] {
        rwmos::EmulatedBoard board;
        return fuzz::snapshot(board);
    }();
    return seen;
}

std::uint64_t hash_of(Bytes bytes) {
    std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a
    for (const std::uint8_t b : bytes) {
        h ^= b;
        h *= 0x100000001b3ULL;
    }
    return h;
}

void serve_as_datagram(Bytes request) {
    rwmos::EmulatedBoard board;
    rwmos::FrameServer server(board);
    FUZZ_CHECK(fuzz::first_difference(board, fresh_board(), 0) == nullptr,
               "a fresh board shows what every fresh board shows");
    std::vector<std::uint8_t> reply;
    const FrameError served = server.serve(request, reply);

    objif::Frame frame;
    std::size_t consumed = 0;
    bool need_more = false;
    FUZZ_CHECK(objif::decode_frame(reply, frame, consumed, need_more) == FrameError::kNone,
               "the reply is a well-formed frame");
    FUZZ_CHECK(consumed == reply.size(), "the reply is exactly one frame");
    FUZZ_CHECK((frame.opcode & objif::kReplyFlag) != 0, "the reply carries the reply flag");
    if (served == FrameError::kNone) return;

    objif::ErrorReply error;
    FUZZ_CHECK(frame.opcode == (objif::kReplyFlag | static_cast<std::uint16_t>(objif::Opcode::kError)),
               "a rejected request is answered with an Error reply");
    FUZZ_CHECK(objif::decode(frame.payload, error) == FrameError::kNone, "the Error reply decodes");
    FUZZ_CHECK(error.reason == served, "the Error reply names the reason");
    FUZZ_CHECK(fuzz::first_difference(board, fresh_board(), hash_of(request)) == nullptr,
               "a rejected request changes no observable state");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const Bytes bytes(data, size);
    decode_as_stream(bytes);
    serve_as_datagram(bytes);
    return 0;
}
