#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Draws the figures of docs/compensation.md with `apcictl run --svg` from the programs in
# docs/figures/ (tc-*.nc, tool list tc-figures.tools). The test
# apcictl.ApcictlRun.CompensationFiguresAreCurrent fails when they are stale.
# Usage: scripts/tc_figures.sh   (needs build/bin/apcictl, or APCICTL=path)
set -euo pipefail
cd "$(dirname "$0")/.."
apcictl="${APCICTL:-./build/bin/apcictl}"
for program in docs/figures/tc-*.nc; do
  status=0
  "$apcictl" run "$program" --tools docs/figures/tc-figures.tools --svg "${program%.nc}.svg" \
    >/dev/null 2>&1 || status=$?
  # tc-*-error.nc programs show an error: they end with exit code 1.
  case "$program" in
    *-error.nc) [ "$status" -eq 1 ] || { echo "$program: exit $status, expected 1" >&2; exit 1; } ;;
    *) [ "$status" -eq 0 ] || { echo "$program: exit $status" >&2; exit 1; } ;;
  esac
  echo "${program%.nc}.svg"
done
