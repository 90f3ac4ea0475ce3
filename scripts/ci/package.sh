#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The packaging stage (docs/packaging.md, docs/hardening.md "Debian package"):
# builds the Debian packages of debian/ with dpkg-buildpackage in a copy of
# the checkout (build-deb/apci8001-VERSION; the packages land in build-deb/,
# nothing is written outside the checkout; the package build runs the tests of
# debian/rules), checks them with lintian, runs the autopkgtest of debian/tests
# (which installs libapci1, libapci-dev, apci-tools and python3-apci on this
# machine and runs the installed tools, the C consumer, the Python package and
# its HIL example against the installed files only), and builds the Python
# module with pip into a venv from pyproject.toml. The packages are purged
# again at the end unless APCI_KEEP_PACKAGE=1.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_ci_deps
# Only this stage needs them: dh and its helpers, and the package checker.
apci_install_packages debhelper lintian dh-python pandoc

version=$(dpkg-parsechangelog -S Version)
project_version=$(sed -n 's/^project(apci8001 VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
if [ "$version" != "$project_version" ]; then
  echo "package: debian/changelog is at version $version but CMakeLists.txt at $project_version;" \
    "add a debian/changelog entry for $project_version (docs/packaging.md, \"New version\")" >&2
  exit 1
fi
# The library's package is named after its SONAME, libapci.so.N (APCI_SOVERSION of
# driver/driver.cmake).
soversion=$(sed -n 's/^set(APCI_SOVERSION \([0-9]\+\))$/\1/p' driver/driver.cmake)
library_package="libapci$soversion"
if [ -z "$soversion" ] || ! grep -qx "Package: $library_package" debian/control; then
  echo "package: driver/driver.cmake sets APCI_SOVERSION '$soversion' but debian/control" \
    "has no package $library_package; rename the library's package" \
    "(docs/packaging.md, \"New SONAME\")" >&2
  exit 1
fi
arch=$(dpkg-architecture -qDEB_HOST_ARCH)
packages=("$library_package" libapci-dev apci-tools python3-apci)

# copy_tree DIR: the source tree into DIR: the files git knows (tracked, and new
# ones not ignored), as they are in the working tree; no build directories.
copy_tree() {
  mkdir -p "$1"
  git ls-files -z --cached --others --exclude-standard |
    while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
    tar --null -T - -cf - | tar -xf - -C "$1"
}
out=build-deb
src="$out/apci8001-$version"
rm -rf "$out"
copy_tree "$src"

echo "== dpkg-buildpackage -us -uc in $src (log: $out/build.log)"
# ccache as the compiler launcher (debian/rules, APCI_COMPILER_LAUNCHER);
# every symbol libapci exports must be in debian/libapci1.symbols and the
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
for p in "${packages[@]}" "$library_package-dbgsym" apci-tools-dbgsym python3-apci-dbgsym; do
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
    DEBIAN_FRONTEND=noninteractive apt-get purge -y -qq "${packages[@]}" >/dev/null 2>&1 || true
  fi
}
trap cleanup EXIT

# The single package the CPack path (cmake/packaging.cmake) builds holds the
# same files: a leftover one is removed first.
if dpkg-query -W -f='${Status}' apci8001 2>/dev/null | grep -q "install ok installed"; then
  DEBIAN_FRONTEND=noninteractive apt-get remove -y -qq apci8001 >/dev/null
fi

echo "== autopkgtest (debian/tests: tools, c-consumer, python) on this machine, with the built packages"
# autopkgtest installs the .debs given and each test's Depends, then runs the tests from the
# source package against the installed files only (-B: the source is not built again; the null
# runner: this machine is the testbed, as in CI's fresh container).
apci_install_packages autopkgtest
debs=()
for p in "${packages[@]}"; do debs+=("$(realpath "$out/${p}_${version}_${arch}.deb")"); done
start=$SECONDS
rc=0
autopkgtest -B --output-dir "$out/autopkgtest" "${debs[@]}" "$(realpath "$out/apci8001_${version}.dsc")" -- null \
  >"$out/autopkgtest.log" 2>&1 || rc=$?
sed -n '/^[a-z-]* *\(PASS\|FAIL\|SKIP\)/p' "$out/autopkgtest.log"
if [ "$rc" != 0 ]; then
  tail -n 60 "$out/autopkgtest.log" >&2
  echo "package: autopkgtest failed ($rc); the whole log is $out/autopkgtest.log" >&2
  exit 1
fi
echo "autopkgtest: passed in $((SECONDS - start)) s"

# Still installed: nothing in /etc enabled for every user, the copyright files.
if [ -e /etc/systemd/user/default.target.wants/rwmos-emu.service ] ||
   [ -e /etc/systemd/user/sockets.target.wants/rwmos-emu.socket ]; then
  echo "installing apci-tools enabled rwmos-emu for every user; it must stay disabled" >&2; exit 1
fi
for p in "${packages[@]}"; do
  grep -q '^License: MIT' "/usr/share/doc/$p/copyright" ||
    { echo "/usr/share/doc/$p/copyright is missing or names no license" >&2; exit 1; }
done

echo "== pip install --no-build-isolation into a venv (pyproject.toml, meson-python)"
# As a pip user without a package index: Debian's build backend and pybind11 through the
# system site packages, the module built from a fresh copy of the source tree.
apci_install_packages python3-mesonpy python3-venv python3-pip
pip_src="$out/pip-src"
rm -rf "$pip_src"
copy_tree "$pip_src"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
start=$SECONDS
touch "$work/pip-started"
if ! (cd "$pip_src" && "$work/venv/bin/pip" install --no-build-isolation --no-index .) \
    >"$out/pip.log" 2>&1; then
  tail -n 40 "$out/pip.log" >&2
  echo "package: pip install failed; the whole log is $out/pip.log" >&2
  exit 1
fi
# What pip wrote into the tree (meson-python's native file and build directory, build-pip/)
# is all ignored by .gitignore and none of it tracked, so a user's checkout stays clean.
written=$(cd "$pip_src" && find . -type f -newer "$work/pip-started" -printf '%P\n' | LC_ALL=C sort)
dirty=""
if [ -n "$written" ]; then
  dirty=$( {
    LC_ALL=C comm -12 <(printf '%s\n' "$written") <(git ls-files | LC_ALL=C sort)
    printf '%s\n' "$written" | { git check-ignore --stdin --non-matching --verbose || true; } |
      sed -n 's/^::\t//p'
  } | LC_ALL=C sort -u)
fi
if [ -n "$dirty" ]; then
  echo "package: pip install wrote files into the checkout that git would show" \
    "(tracked, or not in .gitignore):" >&2
  printf '  %s\n' $dirty >&2
  exit 1
fi
(cd "$work" && "$work/venv/bin/python" - "$work/venv" <<'PY'
import importlib.metadata, pathlib, sys, apci
venv = pathlib.Path(sys.argv[1]).resolve()
where = pathlib.Path(apci.__file__).resolve()
assert venv in where.parents, f"apci from {where}, not from the venv {venv}"
assert importlib.metadata.version("apci") == apci.__version__
with apci.open() as board:
    board.write(1300, 1, 1, 7, 2.5)
    assert board.read("tc.group[1].radius") == 2.5
print("pip: apci", apci.__version__, "from", where.parent)
PY
)
echo "pip install: built and imported in $((SECONDS - start)) s"
echo "package: built, lint-clean, installed; autopkgtest and the pip build passed"
