#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Unpacks LinuxCNC's standalone interpreter rs274 for the differential test of tool radius
# compensation (tests/compensation, docs/testing.md): Debian 12's linuxcnc-uspace and
# libboost-python1.74.0, fetched with `apt-get download` and unpacked with `dpkg -x` into
# BUILD_DIR/linuxcnc. Nothing of LinuxCNC is installed; the shared libraries rs274 takes from
# the system (libpython3.11, libedit2, libtirpc3) are, like the project's other packages.
# Idempotent and quiet. Where the packages cannot be had (no network, no apt), it says so and
# the test skips with a message.
# Usage: scripts/fetch_linuxcnc.sh [BUILD_DIR]   (default: build)
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/deps.sh
dest="$(cd "${1:-build}" 2>/dev/null && pwd)/linuxcnc"
if [ -x "$dest/usr/bin/rs274" ]; then exit 0; fi
fail() {
  echo "note: LinuxCNC's rs274 not unpacked ($1); the differential test will skip" >&2
  exit 0
}
command -v apt-get >/dev/null 2>&1 && command -v dpkg >/dev/null 2>&1 || fail "no apt-get/dpkg"
apci_install_packages libpython3.11 libedit2 libtirpc3 || fail "its libraries could not be installed"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
packages=(linuxcnc-uspace libboost-python1.74.0)
download() { (cd "$tmp" && apt-get download -qq "${packages[@]}" >/dev/null 2>&1); }
if ! download; then
  # The package lists may not be there yet on a fresh machine.
  sudo=""
  [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && sudo="sudo"
  $sudo apt-get update -qq >/dev/null 2>&1
  download || fail "apt-get download ${packages[*]} failed"
fi
mkdir -p "$tmp/root"
for deb in "$tmp"/*.deb; do
  dpkg -x "$deb" "$tmp/root" || fail "dpkg -x $(basename "$deb") failed"
done
[ -x "$tmp/root/usr/bin/rs274" ] || fail "the package has no usr/bin/rs274"
rm -rf "$dest"
mkdir -p "$(dirname "$dest")"
mv "$tmp/root" "$dest"
echo "unpacked LinuxCNC's rs274 into $dest"
