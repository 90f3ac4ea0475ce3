#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job on the embedded emulator: the seed's wr_quad_disc.nc (without its #OTC lines)
# with its tool list, through `apcictl run`; the summary on standard output, the plot and the
# executed path in out/.
set -euo pipefail
cd "$(dirname "$0")"
source scripts/deps.sh
apci_install_deps
apci_build build >/dev/null
mkdir -p out
./build/bin/apcictl run examples/wr_quad_disc.nc --tools examples/tools/wr_quad_disc.tools \
  --svg out/wr_quad_disc.svg --json out/wr_quad_disc.json
echo "wrote out/wr_quad_disc.svg and out/wr_quad_disc.json"
