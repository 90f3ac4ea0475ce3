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
      echo "Installs what building needs (apt-get), builds apcictl and the libraries it links in"
      echo "build/ (the first time about 2.5 minutes on 2 cores, then seconds; no tests: ./test.sh),"
      echo "and runs the main job on the embedded emulator: examples/wr_quad_disc.nc and"
      echo "examples/otc/wr_quad_disc.nc through apcictl run; the summaries on standard output,"
      echo "plots, paths and the worn tool list in out/."
      exit 0 ;;
    *)
      echo "run.sh: takes no arguments (got '$1'); ./run.sh --help says what it does" >&2
      exit 2 ;;
  esac
fi
source scripts/deps.sh
apci_install_run_deps
# Builds only what it runs: apcictl and the libraries it links (no tests,
# benchmarks or fuzzers; ./test.sh builds those in the same build/).
if [[ ! -x build/bin/apcictl ]]; then
  echo "run.sh: first build of apcictl and libapci (about 110 files): about 2.5 minutes on 2 cores;"
  echo "        later runs rebuild only what changed and start in seconds"
fi
# A build/ of its own leaves the tests out (./test.sh turns them on); one that
# ./test.sh made keeps them (nothing is rebuilt for it).
fresh=()
[[ -f build/CMakeCache.txt ]] || fresh=(-DAPCI_BUILD_TESTS=OFF -DAPCI_BUILD_BENCH=OFF)
apci_configure build "${fresh[@]}"
cmake --build build -j"$(nproc)" --target apcictl
mkdir -p out
./build/bin/apcictl run examples/wr_quad_disc.nc --tools examples/tools/wr_quad_disc.tools \
  --svg out/wr_quad_disc.svg --json out/wr_quad_disc.json
echo "wrote out/wr_quad_disc.svg and out/wr_quad_disc.json"
./build/bin/apcictl run examples/otc/wr_quad_disc.nc --tools examples/tools/wr_quad_disc.tools \
  --plc examples/otc/plc/wr_quad_disc.plc --svg out/otc_wr_quad_disc.svg --svg-cycles \
  --json out/otc_wr_quad_disc.json --tools-out out/otc_wr_quad_disc.tools
echo "wrote out/otc_wr_quad_disc.svg, .json and .tools (the tool list with the wear folded in)"
