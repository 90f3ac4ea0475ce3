#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is missing, builds everything, runs every test.
# APCI_WERROR=ON ./test.sh fails the build on any compiler warning, as CI does
# (.ci/run sets it; docs/hardening.md, "Warnings").
set -euo pipefail
cd "$(dirname "$0")"
source scripts/deps.sh
apci_install_deps
apci_build build
# LinuxCNC's rs274 for the differential test of the compensation (skipped where it cannot be had).
scripts/fetch_linuxcnc.sh build
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 600
