#!/bin/sh
# SPDX-License-Identifier: MIT
# A host tool builds without the emulator (docs/design.md section 2, "Shared declarations"):
#   check_includes.sh SOURCE_DIR
# fails, listing file:line, where a file under driver/ or tools/ includes an emulator header
# (rwmos/...). Allowed: the in-process transport (driver/src/transport_inproc.cpp), the daemon
# (tools/rwmos-emu/) and the figure generators (tools/figures/), which are the emulator's own
# users.
set -u
src="${1:-}"
if [ -z "$src" ] || [ ! -d "$src/driver" ] || [ ! -d "$src/tools" ]; then
  echo "usage: check_includes.sh SOURCE_DIR (with driver/ and tools/)" >&2
  exit 2
fi
cd "$src" || exit 2
hits="$(grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]rwmos/' driver tools |
  grep -vE '^driver/src/transport_inproc[.]cpp:|^tools/rwmos-emu/|^tools/figures/')"
if [ -n "$hits" ]; then
  printf '%s\n' "$hits"
  echo "host code includes emulator headers (above): include the shared declaration from" \
    "objif/ instead (docs/design.md section 2, \"Shared declarations\")" >&2
  exit 1
fi
exit 0
