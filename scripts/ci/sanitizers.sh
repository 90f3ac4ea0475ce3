#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The sanitizer stages (docs/hardening.md):
#   asan  build-asan: the whole test suite under AddressSanitizer +
#         UndefinedBehaviorSanitizer (gcc), including the fuzz corpus and
#         crash replays;
#   tsan  build-tsan: the test programs that run threads (ctest label
#         "threaded": daemon, transports, the driver's thread tests) under
#         ThreadSanitizer.
# Usage: scripts/ci/sanitizers.sh [asan] [tsan]   (default: both)
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_deps

# Every report fails its test: no recovery, leaks count, stacks symbolised.
export ASAN_OPTIONS="verify_asan_link_order=0:detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"

# -O1 -g1: half the compile time of -O2 -g (the stage's cost is mostly the
# build), line tables enough for symbolised reports; NDEBUG as in ./test.sh.
# The test programs' own sources at -O0 (APCI_TEST_COMPILE_OPTIONS): under the
# sanitizers gcc compiles a GoogleTest file at -O0 in half the time of -O1,
# and the code they test (libraries, tools, tests/support) and the sources
# named OPTIMIZED keep -O1.
# The Python package is left out: its extension would be loaded into an
# uninstrumented interpreter (the sanitizer runtime not first, the
# interpreter's own allocations counted as leaks); the C++ it binds (libapci,
# the run executor) runs under the sanitizers through the C++ tests.
configure() {  # configure BUILD_DIR SANITIZERS
  # shellcheck disable=SC2046
  cmake -S . -B "$1" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAPCI_SANITIZE="$2" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DAPCI_TEST_COMPILE_OPTIONS=-O0 \
    -DAPCI_BUILD_BENCH=OFF -DAPCI_BUILD_PYTHON=OFF -DAPCI_WERROR=ON $(apci_launcher_args) >/dev/null
}

run_asan() {
  configure build-asan address,undefined
  cmake --build build-asan -j"$(nproc)" >/dev/null
  # The gouge agreement (1,700 programs, 4 minutes of test time under ASan) is there for its
  # statistics, which ./test.sh gives; here its code runs on the first 10
  # programs of each family.
  GOUGE_SEEDS=1000:10 ctest --test-dir build-asan --output-on-failure -j"$(nproc)" --timeout 900
}

run_tsan() {
  configure build-tsan thread
  cmake --build build-tsan -j"$(nproc)" --target threaded_tests >/dev/null
  ctest --test-dir build-tsan --output-on-failure -j"$(nproc)" --timeout 900 -L threaded --no-tests=error
}

stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(asan tsan)
for stage in "${stages[@]}"; do
  case "$stage" in
    asan) echo "== AddressSanitizer + UndefinedBehaviorSanitizer: the whole suite"; run_asan ;;
    tsan) echo "== ThreadSanitizer: the threaded tests"; run_tsan ;;
    *) echo "usage: $0 [asan] [tsan]" >&2; exit 2 ;;
  esac
done
