#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The release stage (docs/hardening.md, "Release build"): what a user gets
# from `cmake -S . -B b -DCMAKE_BUILD_TYPE=Release && cmake --build b` (-O3,
# every program: libraries, tools, tests, benchmarks), built in build-release
# with gcc 12 and -DAPCI_WERROR=ON, so a warning that only the optimiser of a
# Release build sees (gcc's flow-sensitive warnings, -O3 inlining) fails CI
# before it reaches a user; then the whole suite runs on the -O3 code.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_deps

build="build-release"
# shellcheck disable=SC2046
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DAPCI_WERROR=ON \
  -DAPCI_BUILD_TESTS=ON -DAPCI_BUILD_BENCH=ON $(apci_launcher_args) >/dev/null
start=$SECONDS
cmake --build "$build" -j"$(nproc)" >/dev/null
echo "release: built in $((SECONDS - start)) s, no warning"
# LinuxCNC's rs274 for the differential test: ./test.sh's copy when there is one.
if [ -x build/linuxcnc/usr/bin/rs274 ] && [ ! -e "$build/linuxcnc" ]; then
  cp -a build/linuxcnc "$build/"
fi
scripts/fetch_linuxcnc.sh "$build"
start=$SECONDS
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" --timeout 600
echo "release: tests passed in $((SECONDS - start)) s"
