#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job on the embedded emulator: wr_quad_disc.nc of [ISG-OTC-EN] (without its #OTC lines)
# with its tool list, through `apcictl run`; then the complete program with its #OTC lines
# and the PLC's 2 mm (docs/otc.md); the summaries on standard output, plots and paths in out/.
set -euo pipefail
cd "$(dirname "$0")"
if [[ $# -gt 0 ]]; then
  case "$1" in
    -h|--help)
      echo "usage: ./run.sh"
      echo "Installs what is missing (apt-get), builds, and runs the main job on the embedded"
      echo "emulator: examples/wr_quad_disc.nc and examples/otc/wr_quad_disc.nc through apcictl run;"
      echo "the summaries on standard output, plots, paths and the worn tool list in out/."
      exit 0 ;;
    *)
      echo "run.sh: takes no arguments (got '$1'); ./run.sh --help says what it does" >&2
      exit 2 ;;
  esac
fi
source scripts/deps.sh
apci_install_deps
apci_build build >/dev/null
mkdir -p out
./build/bin/apcictl run examples/wr_quad_disc.nc --tools examples/tools/wr_quad_disc.tools \
  --svg out/wr_quad_disc.svg --json out/wr_quad_disc.json
echo "wrote out/wr_quad_disc.svg and out/wr_quad_disc.json"
./build/bin/apcictl run examples/otc/wr_quad_disc.nc --tools examples/tools/wr_quad_disc.tools \
  --plc examples/otc/plc/wr_quad_disc.plc --svg out/otc_wr_quad_disc.svg --svg-cycles \
  --json out/otc_wr_quad_disc.json --tools-out out/otc_wr_quad_disc.tools
echo "wrote out/otc_wr_quad_disc.svg, .json and .tools (the tool list with the wear folded in)"
