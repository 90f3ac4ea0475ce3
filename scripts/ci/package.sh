#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The packaging stage (docs/hardening.md, "Debian package"): builds the .deb
# with CPack in build-pkg (prefix /usr, no tests), installs it on this
# machine, and runs the installed tools and one example against the installed
# files only: apcictl --help, rwmos-emu --help, the man pages, pkg-config and
# the CMake package, and examples/pcap_tc_init.c compiled against the
# installed headers and library. The package is removed again at the end
# unless APCI_KEEP_PACKAGE=1.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_ci_deps

build=build-pkg
# shellcheck disable=SC2046
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_INSTALL_PREFIX=/usr \
  -DAPCI_BUILD_TESTS=OFF -DAPCI_BUILD_BENCH=OFF $(apci_launcher_args) >/dev/null
cmake --build "$build" -j"$(nproc)" >/dev/null
rm -f "$build"/apci8001_*.deb
(cd "$build" && cpack -G DEB >/dev/null)
deb=$(ls "$build"/apci8001_*.deb)
echo "== built $deb"
dpkg-deb --info "$deb" | sed -n '/Package:/,$p'
dpkg-deb --contents "$deb" | awk '{print $6}'

work="$(mktemp -d)"
cleanup() {
  rm -rf "$work"
  if [ "${APCI_KEEP_PACKAGE:-0}" != 1 ]; then
    DEBIAN_FRONTEND=noninteractive apt-get remove -y -qq apci8001 >/dev/null 2>&1 || true
  fi
}
trap cleanup EXIT

echo "== installing"
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$(realpath "$deb")" >/dev/null

# From here on only installed files: run from an empty directory with a PATH
# that does not reach the build tree.
cd "$work"
export PATH=/usr/sbin:/usr/bin:/sbin:/bin
unset APCI_DEVICE LD_LIBRARY_PATH

echo "== installed tools"
test "$(command -v apcictl)" = /usr/bin/apcictl
apcictl --help >/dev/null
apcictl --version
test "$(command -v rwmos-emu)" = /usr/bin/rwmos-emu
rwmos-emu --help >/dev/null
echo "rwmos-emu --help: ok"
for page in $(dpkg -L apci8001 | grep '/man1/'); do
  man -l "$page" >/dev/null 2>&1 || { echo "man page $page does not render" >&2; exit 1; }
  echo "man page: $page"
done

echo "== udev rule and systemd unit"
test -f /usr/lib/udev/rules.d/60-apci8001.rules
echo "udev rule: /usr/lib/udev/rules.d/60-apci8001.rules"
unit=$(dpkg -L apci8001 | grep 'rwmos-emu.service$') || { echo "the systemd unit is not packaged" >&2; exit 1; }
echo "systemd unit: $unit"

echo "== example against the installed package: pcap_tc_init (pkg-config apci $(pkg-config --modversion apci))"
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror -o pcap_tc_init "$OLDPWD/examples/pcap_tc_init.c" $(pkg-config --cflags --libs apci)
# The loader finds the installed library in the multiarch directory, reached
# as /usr/lib/... or, on a merged-/usr system, /lib/... (the same file).
used=$(ldd ./pcap_tc_init | sed -n 's/^\s*libapci\.so\.0 => \(\S*\).*/\1/p')
installed=$(dpkg -L apci8001 | grep '/libapci\.so\.0$')
[ -n "$used" ] && [ "$(realpath "$used")" = "$(realpath "$installed")" ] || {
  echo "pcap_tc_init uses '${used:-no libapci}', not the installed $installed" >&2; exit 1; }
./pcap_tc_init
echo "== the same example through the installed daemon (unix:$work/emu.sock)"
rwmos-emu --socket "$work/emu.sock" --log-level warn &
daemon=$!
for _ in $(seq 100); do [ -S "$work/emu.sock" ] && break; sleep 0.1; done
./pcap_tc_init "unix:$work/emu.sock"
apcictl --device "unix:$work/emu.sock" status
kill "$daemon" && wait "$daemon"

echo "== CMake package: find_package(apci)"
mkdir consumer && cat > consumer/CMakeLists.txt <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(consumer C)
find_package(apci 0.1 REQUIRED)
add_executable(consumer main.c)
target_link_libraries(consumer PRIVATE apci::apci)
CMAKE
printf '#include <stdio.h>\n#include "apci/apci.h"\nint main(void) { printf("libapci %%s\\n", apci_version()); return 0; }\n' > consumer/main.c
cmake -S consumer -B consumer/build >/dev/null && cmake --build consumer/build >/dev/null && ./consumer/build/consumer

echo "== apcictl script against the embedded emulator"
printf 'write 1300 1 1 8 5\nwrite 1300 1 1 7 2.5\nread 1300 1 1 7\nstatus\n' | apcictl script -
echo "== apcictl run: an NC program with its path plot, by the installed apcictl"
apcictl run "$OLDPWD/examples/wr_quad_disc.nc" --tools "$OLDPWD/examples/tools/wr_quad_disc.tools" \
  --svg run.svg --json run.json
test -s run.svg && test -s run.json
echo "package: installed, tools and example ran from the installed files"
