#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Refreshes the seed corpora in corpus/ from the tests and the examples:
#   corpus/nc/              examples/*.nc and the NC programs in tests/nc/*.cpp
#   corpus/tools/           examples/tools/*.tools and the tool lists in tests/nc/tools_test.cpp
#   corpus/apcictl_script/  the scripts in tests/tools/apcictl_test.cpp
#   corpus/frame/           wire frames (docs/wire-frame.md): object reads and writes of the
#                           objects the tests use, replies, a two-frame stream, a bad CRC
#   corpus/mailbox/         dual-port RAM windows (docs/dpram.md) as fuzz_mailbox.cpp reads
#                           them: a served one with a reply, pending requests, bad lengths,
#                           sequences out of step, another layout version, a held lock
# Each seed is named by the SHA-1 of its content, so a rerun adds only new ones.
# A maintainer's tool: the build and CI use the committed files.
import hashlib
import pathlib
import re
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORPUS = pathlib.Path(__file__).resolve().parent / "corpus"

# A run of adjacent C++ string literals ("a" "b" joins to "ab").
LITERALS = re.compile(r'(?:"(?:[^"\\\n]|\\.)*"\s*)+')
ONE = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
ESCAPES = {"n": "\n", "t": "\t", "r": "\r", '"': '"', "\\": "\\", "'": "'", "0": "\0"}


def unescape(body):
    return re.sub(r"\\(.)", lambda m: ESCAPES.get(m.group(1), m.group(1)), body)


def literals(path):
    text = path.read_text(encoding="utf-8")
    for run in LITERALS.finditer(text):
        yield "".join(unescape(m.group(1)) for m in ONE.finditer(run.group(0)))


def save(kind, content):
    data = content.encode("utf-8") if isinstance(content, str) else content
    if not data:
        return
    out = CORPUS / kind
    out.mkdir(parents=True, exist_ok=True)
    (out / hashlib.sha1(data).hexdigest()).write_bytes(data)


MAGIC, VERSION, REPLY = 0x49435041, 1, 0x8000
READ, WRITE, SPOOL, DIRECT, SSF, CLOCK, TRACE, ERROR = 1, 2, 3, 4, 5, 6, 7, 0x7FFF
INT32, DOUBLE = 1, 2


def frame(opcode, sequence, payload):
    head = struct.pack("<IHHII", MAGIC, VERSION, opcode, sequence, len(payload)) + payload
    return head + struct.pack("<I", zlib.crc32(head))


def descriptor(bus, dev, idx, sub, handle=0):
    return struct.pack("<iiiiI", bus, dev, idx, sub, handle)


def value(v):
    return struct.pack("<Bi", INT32, v) if isinstance(v, int) else struct.pack("<Bd", DOUBLE, v)


def frames():
    objects = [((1300, 1, 1, 8), INT32, 5), ((1300, 1, 1, 7), DOUBLE, 2.5),
               ((1300, 1, 1, 3), INT32, 1), ((1300, 0, 12, 0), INT32, 18),
               ((1300, 0, 20, 0), DOUBLE, 30.0), ((1300, 0, 1, 0), INT32, 1),
               ((1000, 0, 1, 0), INT32, 0), ((1300, 1, 0, 1), INT32, 0)]
    for seq, (address, tag, v) in enumerate(objects, start=1):
        yield frame(READ, seq, descriptor(*address) + bytes([tag]))
        yield frame(WRITE, seq, descriptor(*address) + value(v))
    yield frame(READ | REPLY, 7, struct.pack("<II", 0, 0x10001) + value(5))
    yield frame(WRITE | REPLY, 8, struct.pack("<II", 0x08000022, 0x10001))
    yield frame(ERROR | REPLY, 9, struct.pack("<IB", 0x0F000100, 5))
    yield frame(WRITE, 10, descriptor(1300, 1, 1, 8) + value(3)) + frame(READ, 11, descriptor(1300, 1, 1, 8) + bytes([INT32]))
    # Motion payloads (docs/motion.md "Wire payloads"): spool G01/G02, JA/JS, SSF 2001,
    # clock step / run until idle / query / trace on, trace read.
    axes8 = lambda *v: struct.pack("<8d", *(list(v) + [0.0] * (8 - len(v))))
    yield frame(SPOOL, 20, struct.pack("<BBBBI", 1, 0x03, 0, 1, 10) + struct.pack("<d", 600.0)
                + axes8(10.0, 5.0) + struct.pack("<2d", 0.0, 0.0))
    yield frame(SPOOL, 21, struct.pack("<BBBBI", 3, 0x03, 0, 1, 20) + struct.pack("<d", 600.0)
                + axes8(0.0, 10.0) + struct.pack("<2d", 0.0, 5.0))
    yield frame(DIRECT, 22, struct.pack("<HB", 1, 0x01) + struct.pack("<d", 0.0) + axes8(3.0))
    yield frame(DIRECT, 23, struct.pack("<HB", 2, 0x00) + struct.pack("<d", 0.0) + axes8())
    yield frame(SSF, 24, struct.pack("<Bi", 0x03, 2001))
    for mode, cycles in ((0, 100), (1, 100000), (2, 0), (3, 64), (4, 0)):
        yield frame(CLOCK, 25 + mode, struct.pack("<BQ", mode, cycles))
    yield frame(TRACE, 30, struct.pack("<BI", 0, 16))
    yield frame(TRACE, 31, struct.pack("<BI", 1, 16))
    good = frame(READ, 12, descriptor(1300, 1, 1, 8) + bytes([INT32]))
    yield good[:-1] + bytes([good[-1] ^ 0xFF])  # bad CRC
    yield frame(0x0042, 13, b"")                 # unknown opcode


# fuzz_emulator's operations (tests/fuzz/emulator_harness.h, Op) in its byte encoding.
OP_SPOOL, OP_DIRECT, OP_SSF, OP_STEP, OP_RUN, OP_TRACE, OP_SETUP = 2, 3, 4, 5, 6, 7, 8


# The window as fuzz_mailbox.cpp takes it: flags, the first 0x120 bytes, then the
# window from the reply sequence (0x10200) on.
DRPM, LAYOUT, WINDOW, RECORD = 0x4D505244, 2, 0x20220, 65556


def window(answers=True, version=LAYOUT, state=1, lock=0, req_seq=0, req=b"", req_len=None,
           rep_seq=0, rep=b"", rep_len=None):
    head = struct.pack("<6I", DRPM, version, WINDOW, RECORD, state, 1).ljust(0x40, b"\0")
    head += struct.pack("<I", lock).ljust(0xC0, b"\0")
    head += struct.pack("<3I", req_seq, 0, len(req) if req_len is None else req_len) + req
    head = head[:0x120].ljust(0x120, b"\0")
    tail = struct.pack("<3I", rep_seq, 0, len(rep) if rep_len is None else rep_len) + rep
    return bytes([1 if answers else 0]) + head + tail


def mailboxes():
    reply = frame(READ | REPLY, 1, struct.pack("<II", 0, 0x10001) + value(8))
    request = frame(READ, 1, descriptor(1000, 0, 3, 0) + bytes([INT32]))
    yield window(rep=reply)
    yield window(answers=False)
    yield window(req_seq=5, rep_seq=5, rep=reply)
    yield window(rep=reply, rep_len=RECORD + 4)
    yield window(req_seq=1, rep_seq=0, req=request)
    yield window(req_seq=1, rep_seq=0, req=request, req_len=3)
    yield window(req_seq=9, rep_seq=2)
    yield window(version=1, rep=reply)
    yield window(state=0)
    yield window(lock=4242, rep=reply)


def emu_line(x, y, kind=1):
    return bytes([OP_SPOOL, 0, kind, 0, 0, int(x * 2) & 0xFF, 0, int(y * 2) & 0xFF, 2])


def emu_arc(x, y, cx, cy, kind=3):
    return emu_line(x, y, kind) + bytes([0, 0, int(cx * 2) & 0xFF, 0, int(cy * 2) & 0xFF])


def emu_setup(group=1, tool=0, radius_step=1, right=0):
    return bytes([OP_SETUP, group - 1, tool, radius_step, right])


def emu_step(cycles):
    return bytes([OP_STEP, cycles & 0xFF, cycles >> 8])


EMU_RUN = bytes([OP_RUN, 0x40, 0x42, 0x0F, 0])


def emulator_sequences():
    square = emu_line(10, 0) + emu_line(10, 10) + emu_line(0, 10) + emu_line(0, 0)
    yield square + EMU_RUN
    yield emu_setup() + square + emu_step(100) + EMU_RUN
    yield emu_setup(right=1) + square + bytes([OP_SSF, 0, 1]) + EMU_RUN
    yield emu_setup(2, 1, 3) + emu_line(10, 0) + emu_arc(10, 10, 10, 5) + emu_line(0, 10) + EMU_RUN
    yield emu_setup() + emu_line(10, 0) + emu_step(50) + bytes([OP_DIRECT, 1]) + emu_line(5, 5) + EMU_RUN
    yield emu_setup() + emu_line(4, 0) + emu_line(4, 0.5) + emu_line(-4, 0.5) + EMU_RUN
    yield bytes([OP_TRACE, 0, 64]) + square + emu_step(3000) + bytes([OP_TRACE, 2]) + EMU_RUN
    yield emu_setup() + emu_line(10, 0, kind=0) + emu_line(10, 10) + EMU_RUN


def main():
    for seq in emulator_sequences():
        save("emulator", seq)
    for f in frames():
        save("frame", f)
    for m in mailboxes():
        save("mailbox", m)
    for p in sorted((ROOT / "examples").glob("**/*.nc")):
        save("nc", p.read_bytes())
    for p in sorted((ROOT / "tests" / "nc").glob("*.cpp")):
        for s in literals(p):
            if "\n" in s and re.search(r"\b[GM]\d", s):
                save("nc", s)
    for p in sorted((ROOT / "examples").glob("**/*.tools")):
        save("tools", p.read_bytes())
    for s in literals(ROOT / "tests" / "nc" / "tools_test.cpp"):
        if "wz[" in s:
            save("tools", s)
    for s in literals(ROOT / "tests" / "tools" / "apcictl_test.cpp"):
        if re.match(r"(#|\s|read|write|status|spool|direct|ssf|step)", s) and "\n" in s:
            save("apcictl_script", s)


if __name__ == "__main__":
    main()
