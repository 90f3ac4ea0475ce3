#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The big-endian stage (docs/hardening.md, "Byte order"): builds tests/bigendian's check of
# the little-endian codecs (the wire frame, the dual-port RAM's words, the digits of the JSON
# writer) with the sources it checks for s390x, a big-endian Debian architecture, with Debian's
# cross compiler (g++-s390x-linux-gnu), statically, and runs it under QEMU's user-mode
# emulation (qemu-user). The packages' `Architecture: linux-any` rests on this. Cheap: one
# program of eleven source files, a few seconds of emulation.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_packages g++-s390x-linux-gnu qemu-user libeigen3-dev libfmt-dev zlib1g-dev

out=build-big-endian
rm -rf "$out"
mkdir -p "$out"
# What the check exercises, and what those sources need to link (tests/bigendian/CMakeLists.txt
# links the libraries instead). zlib is not installed for s390x: the check defines crc32.
sources=(
  tests/bigendian/byte_order_check.cpp
  objif/src/frame.cpp objif/src/mailbox.cpp objif/src/status.cpp
  tools/runlib/src/json_writer.cpp tools/runlib/src/text_sink.cpp tools/runlib/src/path.cpp
  tools/runlib/src/ready_pages.cpp
  tools/nc/src/move_time.cpp driver/src/tc_names.cpp
  geometry/src/element.cpp geometry/src/plane.cpp
)
werror=()
[ "$(apci_werror)" = ON ] && werror=(-Werror)
echo "== s390x-linux-gnu-g++ $(s390x-linux-gnu-g++ -dumpversion): ${#sources[@]} sources"
# Headers-only libraries (Eigen, fmt with FMT_HEADER_ONLY) and zlib.h come from the host's
# /usr/include, after the cross compiler's own (-idirafter).
s390x-linux-gnu-g++ -std=c++20 -O2 -Wall -Wextra "${werror[@]}" -static \
  -DFMT_HEADER_ONLY -DAPCI_CHECK_OWN_CRC32 \
  -Iobjif/include -Igeometry/include -Itools/runlib/include -Idriver/include -Itools/nc/include \
  -I/usr/include/eigen3 -idirafter /usr/include \
  "${sources[@]}" -o "$out/byte_order_check"
file "$out/byte_order_check" | grep -q 'MSB.*S/390' || {
  echo "big-endian: $out/byte_order_check is not an s390x program: $(file "$out/byte_order_check")" >&2
  exit 1
}
echo "== qemu-s390x $out/byte_order_check"
qemu-s390x "$out/byte_order_check"
