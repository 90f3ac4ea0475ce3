#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The packaging stage (docs/packaging.md, docs/hardening.md "Debian package"):
# builds the Debian packages of debian/ with dpkg-buildpackage in a copy of
# the checkout (build-deb/apci8001-VERSION; the packages land in build-deb/,
# nothing is written outside the checkout), checks them with lintian, installs
# libapci0, libapci-dev, apci-tools and python3-apci on this machine, and
# runs the installed tools, the installed example and the installed Python
# package against the installed files only. The packages are removed again at the end unless APCI_KEEP_PACKAGE=1.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_ci_deps
# Only this stage needs them: dh and its helpers, and the package checker.
apci_install_packages debhelper lintian dh-python

version=$(dpkg-parsechangelog -S Version)
project_version=$(sed -n 's/^project(apci8001 VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
if [ "$version" != "$project_version" ]; then
  echo "package: debian/changelog is at version $version but CMakeLists.txt at $project_version;" \
    "add a debian/changelog entry for $project_version (docs/packaging.md, \"New version\")" >&2
  exit 1
fi
arch=$(dpkg-architecture -qDEB_HOST_ARCH)
packages=(libapci0 libapci-dev apci-tools python3-apci)

# The source tree: the files git knows (tracked, and new ones not ignored),
# as they are in the working tree; no build directories.
out=build-deb
src="$out/apci8001-$version"
rm -rf "$out"
mkdir -p "$src"
git ls-files -z --cached --others --exclude-standard |
  while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
  tar --null -T - -cf - | tar -xf - -C "$src"

echo "== dpkg-buildpackage -us -uc in $src (log: $out/build.log)"
# ccache as the compiler launcher (debian/rules, APCI_COMPILER_LAUNCHER);
# every symbol libapci exports must be in debian/libapci0.symbols and the
# other way round (check level 4: new or missing symbols fail the build).
launcher=""
command -v ccache >/dev/null 2>&1 && launcher=ccache
start=$SECONDS
if ! (cd "$src" && APCI_COMPILER_LAUNCHER="$launcher" DPKG_GENSYMBOLS_CHECK_LEVEL=4 \
      dpkg-buildpackage -us -uc -j"$(nproc)") >"$out/build.log" 2>&1; then
  tail -n 40 "$out/build.log" >&2
  echo "package: dpkg-buildpackage failed; the whole log is $out/build.log" >&2
  exit 1
fi
echo "built in $((SECONDS - start)) s:"
for p in "${packages[@]}" libapci0-dbgsym apci-tools-dbgsym python3-apci-dbgsym; do
  deb="$out/${p}_${version}_${arch}.deb"
  test -f "$deb" || { echo "package: $deb was not built" >&2; exit 1; }
  printf '  %-40s %8s bytes\n' "$(basename "$deb")" "$(stat -c %s "$deb")"
done
for p in "${packages[@]}"; do
  echo "-- $p"
  dpkg-deb --field "$out/${p}_${version}_${arch}.deb" Depends
  dpkg-deb --contents "$out/${p}_${version}_${arch}.deb" | awk '$1 !~ /^d/ {print "   " $6}' |
    grep -v '/usr/share/doc/apci-tools/\(examples\|figures\)/'
done

echo "== lintian (source and binary packages; any error, warning or info tag fails the stage)"
rc=0
lintian --display-info --pedantic --fail-on error,warning,info \
  "$out/apci8001_${version}_${arch}.changes" >"$out/lintian.txt" 2>&1 || rc=$?
grep -v '^running with root privileges' "$out/lintian.txt" || true
[ "$rc" = 0 ] || { echo "package: lintian has findings (above); docs/packaging.md, \"lintian\"" >&2; exit 1; }
echo "lintian: clean"

work="$(mktemp -d)"
cleanup() {
  rm -rf "$work"
  if [ "${APCI_KEEP_PACKAGE:-0}" != 1 ]; then
    DEBIAN_FRONTEND=noninteractive apt-get remove -y -qq "${packages[@]}" >/dev/null 2>&1 || true
  fi
}
trap cleanup EXIT

echo "== installing ${packages[*]}"
# The single package the CPack path (cmake/packaging.cmake) builds holds the
# same files: a leftover one is removed first.
if dpkg-query -W -f='${Status}' apci8001 2>/dev/null | grep -q "install ok installed"; then
  DEBIAN_FRONTEND=noninteractive apt-get remove -y -qq apci8001 >/dev/null
fi
debs=()
for p in "${packages[@]}"; do debs+=("$(realpath "$out/${p}_${version}_${arch}.deb")"); done
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${debs[@]}" >/dev/null

# From here on only installed files: run from an empty directory with a PATH
# that does not reach the build tree.
cd "$work"
export PATH=/usr/sbin:/usr/bin:/sbin:/bin
unset APCI_DEVICE LD_LIBRARY_PATH
doc=/usr/share/doc/apci-tools
devdoc=/usr/share/doc/libapci-dev

echo "== installed tools"
test "$(command -v apcictl)" = /usr/bin/apcictl
apcictl --help >/dev/null
apcictl --version
test "$(command -v rwmos-emu)" = /usr/bin/rwmos-emu
rwmos-emu --help >/dev/null
echo "rwmos-emu --help: ok"
pages=$(dpkg -L apci-tools | grep '/man1/.*\.1\.gz$')
[ "$(echo "$pages" | wc -l)" = 2 ] || { echo "expected the man pages of apcictl and rwmos-emu, got: $pages" >&2; exit 1; }
for page in $pages; do
  man -l "$page" >/dev/null 2>&1 || { echo "man page $page does not render" >&2; exit 1; }
  echo "man page: $page"
done

echo "== udev rule, systemd unit, documentation, copyright"
rule=$(dpkg -L apci-tools | grep '/udev/rules.d/60-apci8001\.rules$')
test -f "$rule" && echo "udev rule: $rule"
unit=$(dpkg -L apci-tools | grep '/systemd/user/rwmos-emu\.service$') || {
  echo "the systemd user unit is not packaged" >&2; exit 1; }
echo "systemd user unit: $unit"
# Every entry of Documentation= names something installed: a file:// page, or a
# man: page of the package.
for ref in $(sed -n 's|^Documentation=||p' "$unit"); do
  case "$ref" in
    file://*)
      test -f "${ref#file://}" || {
        echo "the unit's Documentation= $ref is not installed" >&2; exit 1; } ;;
    man:*)
      page="${ref#man:}" name="${page%%(*}" section="${page#*(}" section="${section%)}"
      dpkg -L apci-tools | grep -q "/man/man$section/$name\.$section\(\.gz\)\?$" || {
        echo "the unit's Documentation= $ref is not installed" >&2; exit 1; } ;;
    *) echo "the unit's Documentation= $ref is neither file:// nor man:" >&2; exit 1 ;;
  esac
  echo "its documentation: $ref"
done
if [ -e /etc/systemd/user/default.target.wants/rwmos-emu.service ]; then
  echo "installing apci-tools enabled rwmos-emu for every user; it must stay disabled" >&2; exit 1
fi
echo "rwmos-emu.service: installed, not enabled"
for f in "$doc/README.md" "$doc/apcictl.md" "$doc/c-api.md" "$doc/examples/wr_quad_disc.nc" \
  "$devdoc/examples/pcap_tc_init.c"; do
  test -f "$f" || { echo "$f is not installed" >&2; exit 1; }
done
for p in "${packages[@]}"; do
  grep -q '^License: MIT' "/usr/share/doc/$p/copyright" ||
    { echo "/usr/share/doc/$p/copyright is missing or names no license" >&2; exit 1; }
done
echo "documentation, examples and copyright files: installed"

echo "== the installed example against the installed package: pcap_tc_init (pkg-config apci $(pkg-config --modversion apci))"
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror -o pcap_tc_init "$devdoc/examples/pcap_tc_init.c" $(pkg-config --cflags --libs apci)
# The loader finds the installed library in the multiarch directory, reached
# as /usr/lib/... or, on a merged-/usr system, /lib/... (the same file).
used=$(ldd ./pcap_tc_init | sed -n 's/^\s*libapci\.so\.0 => \(\S*\).*/\1/p')
installed=$(dpkg -L libapci0 | grep '/libapci\.so\.0$')
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
echo "== apcictl run: the installed NC example with its path plot, by the installed apcictl"
apcictl run "$doc/examples/wr_quad_disc.nc" --tools "$doc/examples/tools/wr_quad_disc.tools" \
  --svg run.svg --json run.json
test -s run.svg && test -s run.json
echo "== the installed Python package: import apci (Debian's python3), a run with NumPy arrays"
/usr/bin/python3 -c "
import json, pathlib, apci, numpy
where = pathlib.Path(apci.__file__).resolve()
assert str(where).startswith('/usr/lib/python3/dist-packages/apci/'), where
with apci.open() as b:
    b.write(1300, 1, 1, 7, 2.5)
    assert b.read(1300, 1, 1, 7) == 2.5 and b.status(1).ok
r = apci.run('$doc/examples/wr_quad_disc.nc', tools='$doc/examples/tools/wr_quad_disc.tools')
assert r.ok and r.axes.shape == (r.cycles, 8), r.summary()
# The same path as the installed apcictl's run.json above.
want = json.load(open('run.json'))['segments']
assert len(r.segments) == len(want) > 0, (len(r.segments), len(want))
assert (r.segments['end'] == numpy.array([s['end'] for s in want])).all()
print('apci', apci.__version__, 'from', where.parent, '-', r.summary().splitlines()[0])
"
test -f /usr/share/doc/python3-apci/examples/python/test_hil.py
echo "package: built, lint-clean, installed; tools and examples ran from the installed files"
