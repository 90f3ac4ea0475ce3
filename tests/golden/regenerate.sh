#!/bin/sh
# SPDX-License-Identifier: MIT
# Rewrites the golden JSON outputs of tests/golden/expected/ with the apcictl of BUILD_DIR
# (default: build). Only when an output is meant to change: review `git diff` afterwards.
#   tests/golden/regenerate.sh [BUILD_DIR]
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-build}
case $build in /*) ;; *) build=$root/$build ;; esac
if [ ! -x "$build/bin/apcictl" ]; then
    echo "regenerate.sh: $build/bin/apcictl not found: build it first (cmake --build $build --target apcictl)" >&2
    exit 2
fi
out=$(mktemp -d "${TMPDIR:-/tmp}/apci-golden-XXXXXX")
trap 'rm -rf "$out"' EXIT
cmake -DAPCICTL="$build/bin/apcictl" -DSOURCE_DIR="$root" -DOUT_DIR="$out" -DMODE=update \
    -P "$root/tests/golden/golden.cmake"
