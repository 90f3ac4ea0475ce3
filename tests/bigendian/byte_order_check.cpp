// SPDX-License-Identifier: MIT
// The little-endian codecs on any host (objif/byte_order.h): the wire frame's encoder and
// decoder (objif/src/frame.cpp), the dual-port RAM's words (objif/src/mailbox.cpp) and the
// digits of `apcictl run --json` (tools/runlib/src/json_writer.cpp) give the same bytes as on
// x86-64. Built and run natively by the test suite (bigendian.ByteOrderCheck), and built for
// s390x (big-endian) and run under QEMU by scripts/ci/big-endian.sh. Self-contained: no test
// framework, no zlib (none is installed for the foreign architecture; crc32 is defined below,
// the CRC-32 of zlib and of docs/wire-frame.md, bit by bit).
#include <zlib.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "apci/run/json_writer.h"
#include "objif/byte_order.h"
#include "objif/frame.h"
#include "objif/mailbox.h"

#ifdef APCI_CHECK_OWN_CRC32
// zlib's crc32 (reflected polynomial 0xEDB88320, initial and final complement), bit by bit.
extern "C" uLong crc32(uLong crc, const Bytef* buf, uInt len) {
    std::uint32_t c = ~static_cast<std::uint32_t>(crc);
    for (uInt i = 0; i < len; ++i) {
        c ^= buf[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}
#endif

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
    std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
    if (!ok) ++failures;
}

std::string hex(const std::vector<std::uint8_t>& bytes) {
    std::string out;
    char b[4];
    for (const std::uint8_t v : bytes) {
        std::snprintf(b, sizeof b, "%02x", v);
        out += b;
    }
    return out;
}

void frames() {
    // An ObjectWrite request: (1300, 1, 2, 7) handle 0x0A0B0C0D, the double 2.5; sequence
    // 0x01020304. The bytes as x86-64 writes them (magic, version, opcode, sequence, length,
    // payload, CRC-32: all little-endian).
    std::vector<std::uint8_t> payload;
    objif::ByteWriter w(payload);
    w.descriptor(objif::Descriptor{{1300, 1, 2, 7}, 0x0A0B0C0D});
    w.value(objif::Value::of_double(2.5));
    w.u16(0xBEEF);
    w.u64(0x1122334455667788ULL);
    check(hex(payload) ==
              "14050000010000000200000007000000" "0d0c0b0a" "02" "0000000000000440" "efbe"
              "8877665544332211",
          "payload bytes " + hex(payload));
    std::vector<std::uint8_t> frame;
    objif::encode_frame(2, 0x01020304, payload, frame);
    const std::string want_header = "41504349" "0200" "0200" "04030201" "27000000";
    check(hex(frame).rfind(want_header, 0) == 0, "frame header " + hex(frame).substr(0, 40));
    // The CRC of the frame, little-endian, last.
    const auto crc = static_cast<std::uint32_t>(::crc32(0, frame.data(), static_cast<uInt>(frame.size() - 4)));
    check(objif::load_little<std::uint32_t>(frame.data() + frame.size() - 4) == crc, "frame CRC");
    // The CRC x86-64 computes with zlib for this frame (the check's own crc32 on s390x).
    check(crc == 0xd5f21ce0u, "frame CRC is 0xd5f21ce0");
    objif::Frame decoded;
    std::size_t consumed = 0;
    bool need_more = false;
    const auto e = objif::decode_frame(frame, decoded, consumed, need_more);
    check(e == objif::FrameError::kNone && consumed == frame.size() && decoded.opcode == 2 &&
              decoded.sequence == 0x01020304 && decoded.payload == payload,
          "frame decodes to what was encoded");
    objif::ByteReader r(decoded.payload);
    objif::Descriptor d;
    objif::Value v;
    std::uint16_t u16 = 0;
    std::uint64_t u64 = 0;
    check(r.descriptor(d) && d.address.bus == 1300 && d.address.device == 1 &&
              d.address.index == 2 && d.address.subindex == 7 && d.handle == 0x0A0B0C0D,
          "descriptor read back");
    check(r.value(v) == objif::FrameError::kNone && v.is_double() && v.as_double() == 2.5,
          "double read back");
    check(r.u16(u16) && u16 == 0xBEEF && r.u64(u64) && u64 == 0x1122334455667788ULL && r.done(),
          "u16 and u64 read back");
    // A frame of x86-64's bytes decodes the same (the magic "APCI" as bytes).
    std::vector<std::uint8_t> bad = frame;
    bad[0] = 'X';
    check(objif::decode_frame(bad, decoded, consumed, need_more) == objif::FrameError::kBadMagic,
          "bad magic refused");
    const std::vector<std::uint8_t> prefix{0x41, 0x50};
    check(objif::decode_frame(prefix, decoded, consumed, need_more) == objif::FrameError::kShort,
          "a prefix of the magic waits for more");
}

void mailbox_words() {
    alignas(8) std::uint8_t memory[16] = {};
    objif::mailbox::MappedWindow window(memory, sizeof memory, false);
    window.store(4, 0x11223344u);
    check(memory[4] == 0x44 && memory[5] == 0x33 && memory[6] == 0x22 && memory[7] == 0x11,
          "a window word is stored little-endian");
    check(window.load(4) == 0x11223344u, "and loads back");
    memory[8] = 0x01;  // the word 1, as the board writes it
    check(window.load(8) == 1u && window.load_fence(8) == 1u, "a little-endian 1 loads as 1");
    check(window.compare_exchange(8, 1u, 7u) && memory[8] == 7 && memory[11] == 0,
          "compare_exchange compares and stores little-endian");
    check(!window.compare_exchange(8, 1u, 9u) && memory[8] == 7, "and fails on another value");
}

void json_digits() {
    std::FILE* f = std::tmpfile();
    {
        apci::run::JsonRunWriter json(f);
        apci::run::PathSegment s;
        s.block.number = 123456789;
        s.kind = apci::run::SegmentKind::kLine;
        s.start = apci::run::Point(12345.678, -0.5, 0.001);
        s.end = apci::run::Point(98765432.25, 1e-3, -7);
        json.segment(s);
        s.block.number = 123456790;
        s.start = s.end;
        s.end = apci::run::Point(0.1234, 31415926.5358979, 2.718281828459045);
        json.segment(s);
        check(json.finish({}, {}), "JSON written");
    }
    std::rewind(f);
    std::string text;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) text.append(buffer, n);
    std::fclose(f);
    for (const char* number : {"123456789", "123456790", "12345.678", "-0.5", "0.001",
                               "98765432.25", "-7", "0.1234", "31415926.5358979",
                               "2.718281828459045"})
        check(text.find(number) != std::string::npos, std::string("JSON has ") + number);
}

}  // namespace

int main() {
    std::printf("host: %s-endian\n",
                std::endian::native == std::endian::big ? "big" : "little");
    frames();
    mailbox_words();
    json_digits();
    std::printf("%d failed\n", failures);
    return failures == 0 ? 0 : 1;
}
