#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The fuzzing stage (docs/hardening.md): builds the libFuzzer programs with
# clang (libFuzzer + ASan + UBSan) in build-fuzz and runs each one for a
# bounded number of executions, starting from its seed corpus
# (tests/fuzz/corpus/NAME) and every input that once crashed it
# (tests/fuzz/crashes/NAME). Any finding (crash, sanitizer report, broken
# invariant, timeout, memory blow-up) fails the stage; the input is kept in
# build-fuzz/findings/ to be fixed and then added to tests/fuzz/crashes/NAME/.
#
#   APCI_FUZZ_RUNS   executions per fuzzer (default 100000)
#   APCI_FUZZ_SEED   libFuzzer's random seed (default 1: the same tree fuzzes
#                    the same way; 0 picks a new seed each run)
#   APCI_FUZZ_ONLY   run only these fuzzers (space-separated names)
#   APCI_FUZZ_MAX_SECONDS  wall-time bound per fuzzer (default 600): a fuzzer
#                    that has not finished its executions by then fails the
#                    stage (too slow an input path is a finding too), so the
#                    stage can never hold CI up
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_ci_deps

runs="${APCI_FUZZ_RUNS:-100000}"
seed="${APCI_FUZZ_SEED:-1}"
max_seconds="${APCI_FUZZ_MAX_SECONDS:-600}"
build=build-fuzz
# -O1 with line tables only, as OSS-Fuzz builds its fuzzers: the stage's cost is mostly
# compiling every library with coverage and ASan, which -O2 -g doubles; reports stay symbolised.
# shellcheck disable=SC2046
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DAPCI_FUZZ=ON -DAPCI_BUILD_BENCH=OFF -DAPCI_WERROR=ON $(apci_launcher_args) >/dev/null
cmake --build "$build" -j"$(nproc)" --target fuzzers >/dev/null

names=()
if [ -n "${APCI_FUZZ_ONLY:-}" ]; then
  read -r -a names <<<"$APCI_FUZZ_ONLY"
else
  for src in tests/fuzz/fuzz_*.cpp; do
    name="${src#tests/fuzz/fuzz_}"
    names+=("${name%.cpp}")
  done
fi

findings="$build/findings"
logs="$build/fuzz-logs"
mkdir -p "$findings" "$logs"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# fuzz_one NAME: runs one fuzzer; its verdict goes to $work/NAME.verdict ("ok RUNS" or
# "failed"), its messages to standard output and error.
fuzz_one() {
  local name="$1" log start done_runs
  mkdir -p "$work/$name"
  local args=(-runs="$runs" -seed="$seed" -max_total_time="$max_seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096
              -print_final_stats=1 -artifact_prefix="$findings/$name-")
  [ -f "tests/fuzz/$name.dict" ] && args+=(-dict="tests/fuzz/$name.dict")
  local dirs=("$work/$name" "tests/fuzz/corpus/$name")
  [ -d "tests/fuzz/crashes/$name" ] && dirs+=("tests/fuzz/crashes/$name")
  log="$logs/$name.log"
  start=$SECONDS
  if "$build/bin/fuzz_$name" "${args[@]}" "${dirs[@]}" >"$log" 2>&1; then
    done_runs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$log" | tail -n 1)
    if [ -z "$done_runs" ] || [ "$done_runs" -lt "$runs" ]; then
      echo "fuzz_$name: ran ${done_runs:-no} executions in $((SECONDS - start)) s, expected $runs within $max_seconds s" >&2
      echo failed >"$work/$name.verdict"
      return
    fi
    echo "fuzz_$name: $done_runs executions in $((SECONDS - start)) s, no finding"
    echo "ok $done_runs" >"$work/$name.verdict"
  else
    echo "fuzz_$name: FINDING (log: $log; input kept in $findings/)" >&2
    grep -E 'ERROR|runtime error|invariant broken|SUMMARY|Test unit written' "$log" | head -n 20 >&2 || true
    echo failed >"$work/$name.verdict"
  fi
}

# One fuzzer a core at a time (each is single-threaded; the executions and the seed, not the
# time, decide what each one tries, so running side by side changes nothing but the wall time).
for name in "${names[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
  fuzz_one "$name" &
done
wait

failed=0
total=0
for name in "${names[@]}"; do
  read -r verdict done_runs <"$work/$name.verdict" 2>/dev/null || verdict=failed
  if [ "$verdict" = ok ]; then total=$((total + done_runs)); else failed=1; fi
done
[ "$failed" -eq 0 ] || { echo "fuzzing: findings above; fix, then add each input to tests/fuzz/crashes/NAME/" >&2; exit 1; }
echo "fuzzing: ${#names[@]} fuzzers, $total executions, no finding"
