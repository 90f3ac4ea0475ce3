#!/bin/sh
# SPDX-License-Identifier: MIT
# A program is run one way (docs/data-path.md, "One way to run a program"):
#   check_one_run.sh SOURCE_DIR
# fails, listing file:line, where code outside tools/runlib names the program executor
# (apci::run::ProgramExecutor): `apcictl run`, `apcictl diff`, the Python module and the
# benchmarks build a run through apci::run::ProgramRun (program_run.h), which alone constructs
# the executor. Tests may drive the executor itself.
set -u
src="${1:-}"
if [ -z "$src" ] || [ ! -d "$src/tools/runlib" ]; then
  echo "usage: check_one_run.sh SOURCE_DIR (with tools/runlib/)" >&2
  exit 2
fi
cd "$src" || exit 2
hits="$(grep -rnE 'ProgramExecutor[[:space:]]*[a-z_]+[[:space:]]*[({]|ProgramExecutor[[:space:]]*[({]' \
  --include='*.cpp' --include='*.h' --include='*.hpp' tools driver python bench examples |
  grep -vE '^tools/runlib/')"
if [ -n "$hits" ]; then
  printf '%s\n' "$hits"
  echo "a program executor is built outside tools/runlib (above): run the program through" \
    "apci::run::ProgramRun or apci::run::run_program (program_run.h)" >&2
  exit 1
fi
# ProgramRun itself constructs it, and nothing else in tools/runlib/src does.
builders="$(grep -rlE 'executor_\(board|ProgramExecutor[[:space:]]+[a-z_]+[[:space:]]*[({]' \
  tools/runlib/src | sort)"
if [ "$builders" != "tools/runlib/src/program_run.cpp" ]; then
  printf 'built in: %s\n' "$builders"
  echo "the program executor is built elsewhere than tools/runlib/src/program_run.cpp" >&2
  exit 1
fi
exit 0
