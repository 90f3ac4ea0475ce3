#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The static analysis stage (docs/hardening.md): cppcheck over every source
# file of the tree, and clang-tidy with the checks of .clang-tidy over the
# libraries, tools and examples (with every header of ours they include). Any
# finding fails the stage. Only configures (build-analysis/
# compile_commands.json, -DAPCI_WERROR=ON as CI has it, whatever the
# environment says: the clang-tidy cache's keys hold the flags); builds nothing.
#   APCI_TIDY_SCOPE   "code" (default, CI): objif, rwmos_emu, driver, tools, python,
#                     examples; "all": also tests and benchmarks (twice the
#                     time: run it before a release and after touching them)
#   APCI_TIDY_FILES   a regex limiting clang-tidy to some files (overrides the scope)
#   APCI_TIDY_CACHE   "on" (default): a unit whose whole input is unchanged since
#                     it was found clean (scripts/ci/clang-tidy-clean.txt, kept
#                     in git and brought up to date by every clean run) is not
#                     analysed again (scripts/ci/tidy_cache.py); "off": every unit
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/deps.sh
apci_install_ci_deps

build=build-analysis
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DAPCI_WERROR=ON >/dev/null

root="$(pwd)"
case "${APCI_TIDY_SCOPE:-code}" in
  code) scope="^$root/(objif|geometry|rwmos_emu|driver|tools|python|examples)/" ;;
  all) scope="^$root/(objif|geometry|rwmos_emu|driver|tools|python|tests|examples|bench)/" ;;
  *) echo "APCI_TIDY_SCOPE: code or all, not '$APCI_TIDY_SCOPE'" >&2; exit 2 ;;
esac
files="${APCI_TIDY_FILES:-$scope}"

echo "== clang-tidy ($(clang-tidy-14 --version | sed -n 's/.*LLVM version \([0-9.]*\).*/\1/p')): $files"
start=$SECONDS
cache=scripts/ci/clang-tidy-clean.txt
case "${APCI_TIDY_CACHE:-on}" in
  on) cache_in="$cache" ;;
  off) cache_in=/dev/null ;;
  *) echo "APCI_TIDY_CACHE: on or off, not '$APCI_TIDY_CACHE'" >&2; exit 2 ;;
esac
python3 scripts/ci/tidy_cache.py select "$build/compile_commands.json" "$files" "$root" \
  "$cache_in" "$build/tidy-todo.txt" "$build/tidy-keys.txt"
mapfile -t todo <"$build/tidy-todo.txt"
if [ "${#todo[@]}" -gt 0 ]; then
  run-clang-tidy-14 -p "$build" -j "$(nproc)" -quiet "${todo[@]}" >"$build/clang-tidy.log" 2>&1 || {
    sed 's/\x1b\[[0-9;]*m//g' "$build/clang-tidy.log" | grep -E 'warning:|error:' | sort -u >&2
    echo "clang-tidy: findings above (full log: $build/clang-tidy.log)" >&2
    exit 1
  }
fi
# Every unit is clean: their keys go into the cache (commit it with the change).
python3 scripts/ci/tidy_cache.py update "$build/tidy-keys.txt" "$cache"
echo "clang-tidy: no finding ($((SECONDS - start)) s)"

echo "== cppcheck ($(cppcheck --version))"
# readdirCalled: readdir_r is deprecated (glibc, POSIX.1-2024); readdir on a
# DIR* that one thread owns, as every caller here does, is thread-safe.
start=$SECONDS
cppcheck --project="$build/compile_commands.json" --std=c++20 -j "$(nproc)" --quiet \
  --library=googletest --library=posix \
  --enable=warning,performance,portability --inline-suppr --error-exitcode=1 \
  --suppress=missingIncludeSystem --suppress=unmatchedSuppression --suppress=readdirCalled \
  "--suppress=*:/usr/*" -i"$build" --template='{file}:{line}: {severity} ({id}): {message}'
echo "cppcheck: no finding ($((SECONDS - start)) s)"
