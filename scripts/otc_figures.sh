#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Draws the figures of docs/otc.md with `apcictl run --svg --svg-cycles` as listed in
# docs/figures/otc-figures.txt (program, tool list, PLC script, plane). The test
# apcictl.OtcRun.OtcFiguresAreCurrent fails when they are stale.
# Usage: scripts/otc_figures.sh   (needs build/bin/apcictl, or APCICTL=path)
set -euo pipefail
cd "$(dirname "$0")/.."
apcictl="${APCICTL:-./build/bin/apcictl}"
grep -v '^#' docs/figures/otc-figures.txt | while read -r name program tools plc plane; do
  [ -n "$name" ] || continue
  args=(run "$program" --tools "$tools" --plane "$plane" --svg "docs/figures/$name.svg" --svg-cycles)
  [ "$plc" = "-" ] || args+=(--plc "$plc")
  "$apcictl" "${args[@]}" >/dev/null
  echo "docs/figures/$name.svg"
done
