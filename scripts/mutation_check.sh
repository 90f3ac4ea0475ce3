#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Mutation check (docs/testing.md, "Mutation check"): plants the one-line bugs of
# scripts/mutants.txt, one at a time, in a scratch copy of the working tree, rebuilds only the
# test programs each names, runs them (or the CTest tests it names: `run: ctest=REGEX`) and
# reports which mutants the tests kill and which survive. The checkout itself is never written
# to.
#
# Usage: scripts/mutation_check.sh [options]
#   --only ID[,ID...]  check only these mutants
#   --list             list the mutants (id, file, description) and exit
#   --check            check that every mutant's text occurs exactly once in the working tree
#                      (no build) and exit
#   --dir DIR          scratch directory (default: build-mutation): DIR/src is the copy of the
#                      working tree, DIR/build its CMake build directory, DIR/logs the logs,
#                      DIR/report.md the last report
#   --mutants FILE     the mutant list (default: scripts/mutants.txt)
#   --timeout SEC      time limit of one test program run (default: 300)
#   --jobs N           parallel build jobs (default: nproc)
#   -h, --help         this text
# Exit status: 0 every mutant killed by a test; 1 at least one survived; 2 none survived but a
# mutant could not be applied or did not compile, or the check could not run.
set -uo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
work="$root/build-mutation"
mutants_file="$root/scripts/mutants.txt"
only=""
mode="run"
timeout_s=300
jobs="$(nproc 2>/dev/null || echo 2)"

usage() { sed -n '/^# Usage:/,/^[^#]/p' "$0" | sed -n 's/^# \{0,1\}//p'; }
die() { echo "mutation_check: $*" >&2; exit 2; }

while [ $# -gt 0 ]; do
  case "$1" in
    --only) [ $# -ge 2 ] || die "--only needs a list of ids"; only="$2"; shift 2 ;;
    --only=*) only="${1#--only=}"; shift ;;
    --list) mode="list"; shift ;;
    --check) mode="check"; shift ;;
    --dir) [ $# -ge 2 ] || die "--dir needs a directory"; work="$2"; shift 2 ;;
    --mutants) [ $# -ge 2 ] || die "--mutants needs a file"; mutants_file="$2"; shift 2 ;;
    --timeout) [ $# -ge 2 ] || die "--timeout needs seconds"; timeout_s="$2"; shift 2 ;;
    --jobs) [ $# -ge 2 ] || die "--jobs needs a number"; jobs="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) usage >&2; exit 2 ;;
  esac
done
[[ "$timeout_s" =~ ^[1-9][0-9]*$ ]] || die "--timeout: not a number of seconds: $timeout_s"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs: not a number: $jobs"
[ -f "$mutants_file" ] || die "no mutant list: $mutants_file"

# ---- The mutant list

M_ID=() M_FILE=() M_FROM=() M_TO=() M_RUN=() M_BUILD=() M_ABOUT=() M_LINE=() M_EQUIV=()
declare -A seen_id=()

# `\n` in from/to stands for a line break (context spanning two lines).
unescape() { printf '%s' "${1//\\n/$'\n'}"; }

finish_entry() {
  local -n e=$1
  [ ${#e[@]} -eq 0 ] && return 0
  local k
  for k in id file from to run about; do
    [ -n "${e[$k]+x}" ] || die "$mutants_file:${e[line]}: entry without '$k:'"
  done
  [[ "${e[id]}" =~ ^[A-Za-z0-9_.-]+$ ]] || die "$mutants_file:${e[line]}: bad id '${e[id]}'"
  [ -z "${seen_id[${e[id]}]+x}" ] || die "$mutants_file:${e[line]}: id '${e[id]}' used twice"
  [ -n "${e[from]}" ] || die "$mutants_file:${e[line]}: empty 'from:'"
  [ -n "${e[run]}" ] || die "$mutants_file:${e[line]}: empty 'run:'"
  seen_id[${e[id]}]=1
  M_ID+=("${e[id]}")
  M_FILE+=("${e[file]}")
  M_FROM+=("$(unescape "${e[from]}")")
  M_TO+=("$(unescape "${e[to]}")")
  M_RUN+=("${e[run]}")
  if [ -n "${e[build]:-}" ]; then
    M_BUILD+=("${e[build]}")
  else
    local spec targets=""
    for spec in ${e[run]}; do
      [ "${spec%%=*}" = ctest ] || targets+="${spec%%=*} "
    done
    M_BUILD+=("${targets% }")
  fi
  M_ABOUT+=("${e[about]}")
  M_EQUIV+=("${e[equivalent]:-}")
  M_LINE+=("${e[line]}")
  e=()
}

parse_mutants() {
  local -A entry=()
  local n=0 line key value
  while IFS= read -r line || [ -n "$line" ]; do
    n=$((n + 1))
    if [[ "$line" =~ ^[[:space:]]*$ ]]; then finish_entry entry; continue; fi
    [[ "$line" == \#* ]] && continue
    [[ "$line" =~ ^([a-z]+):[[:space:]]*(.*)$ ]] || die "$mutants_file:$n: not 'key: value'"
    key="${BASH_REMATCH[1]}"
    value="${BASH_REMATCH[2]}"
    case "$key" in
      id|file|from|to|run|build|about|equivalent) ;;
      *) die "$mutants_file:$n: unknown key '$key'" ;;
    esac
    [ -n "${entry[$key]+x}" ] && die "$mutants_file:$n: '$key:' twice in one entry"
    [ ${#entry[@]} -eq 0 ] && entry[line]=$n
    entry[$key]="$value"
  done < "$mutants_file"
  finish_entry entry
  [ ${#M_ID[@]} -gt 0 ] || die "$mutants_file: no mutants"
}
parse_mutants

# The selection: indices into M_*.
SEL=()
if [ -n "$only" ]; then
  IFS=',' read -r -a wanted <<< "$only"
  for w in "${wanted[@]}"; do
    found=""
    for i in "${!M_ID[@]}"; do
      if [ "${M_ID[$i]}" = "$w" ]; then SEL+=("$i"); found=1; fi
    done
    [ -n "$found" ] || die "--only: no mutant '$w' (see --list)"
  done
else
  SEL=("${!M_ID[@]}")
fi

if [ "$mode" = "list" ]; then
  printf '%-34s %-40s %s\n' "id" "file" "description"
  for i in "${SEL[@]}"; do
    printf '%-34s %-40s %s\n' "${M_ID[$i]}" "${M_FILE[$i]}" "${M_ABOUT[$i]}"
  done
  exit 0
fi

# Occurrences of $2 in the text $1.
count_in() {
  local text="$1" pattern="$2"
  local rest="${text//"$pattern"/}"
  echo $(( (${#text} - ${#rest}) / ${#pattern} ))
}

# The line of the first occurrence of $2 in $1 (1-based).
line_of() {
  local prefix="${1%%"$2"*}" newlines
  newlines="${prefix//[!$'\n']/}"
  echo $(( ${#newlines} + 1 ))
}

read_file() {  # read_file PATH VAR: the whole file, trailing newlines kept
  local -n out=$2
  out=""
  # shellcheck disable=SC2034  # a nameref: this assigns the caller's variable
  IFS= read -r -d '' out < "$1" || true
}

# Where mutant $1 applies in tree $2: sets WHERE (file:line) or WHY (the error).
locate() {
  local i=$1 tree=$2 text n
  WHERE="" WHY=""
  local path="$tree/${M_FILE[$i]}"
  if [ ! -f "$path" ]; then WHY="no file ${M_FILE[$i]}"; return 1; fi
  read_file "$path" text
  n=$(count_in "$text" "${M_FROM[$i]}")
  if [ "$n" -ne 1 ]; then WHY="original text found $n times in ${M_FILE[$i]} (must be once)"; return 1; fi
  # The line the change starts on (the text may begin on an earlier line of context).
  local from="${M_FROM[$i]}" to="${M_TO[$i]}" k=0
  while [ $k -lt ${#from} ] && [ "${from:$k:1}" = "${to:$k:1}" ]; do k=$((k + 1)); done
  local same="${from:0:$k}"
  same="${same//[!$'\n']/}"
  WHERE="${M_FILE[$i]}:$(( $(line_of "$text" "$from") + ${#same} ))"
}

if [ "$mode" = "check" ]; then
  bad=0
  for i in "${SEL[@]}"; do
    if locate "$i" "$root"; then
      printf '%-34s %s\n' "${M_ID[$i]}" "$WHERE"
    else
      printf '%-34s ERROR: %s\n' "${M_ID[$i]}" "$WHY"
      bad=1
    fi
  done
  [ "$bad" -eq 0 ] || exit 2
  exit 0
fi

# ---- The scratch tree

command -v git >/dev/null 2>&1 || die "git not found"
command -v cmake >/dev/null 2>&1 || die "cmake not found"
command -v timeout >/dev/null 2>&1 || die "timeout (coreutils) not found"
mkdir -p "$work" || die "cannot create $work"
work="$(cd "$work" && pwd)"
src="$work/src" build="$work/build" logs="$work/logs"
case "$work/" in
  "$root/"*)
    # Inside the checkout it must be ignored, or the copy would list itself.
    git -C "$root" check-ignore -q "$work" || die "$work is inside the checkout and not ignored by git"
    ;;
esac
mkdir -p "$src" "$logs"
rm -f "$logs"/*.log

started=$(date +%s)
echo "mutation check: ${#SEL[@]} mutant(s), scratch tree $work"

# Copy every tracked and every untracked, not ignored file of the working tree whose content
# differs (new modification time, so make rebuilds what it must); remove files no longer there.
sync_tree() {
  local f copied=0 removed=0
  local -A listed=()
  while IFS= read -r -d '' f; do
    [ -f "$root/$f" ] || [ -L "$root/$f" ] || continue  # deleted in the working tree
    listed["$f"]=1
    if ! cmp -s "$root/$f" "$src/$f"; then
      mkdir -p "$src/$(dirname "$f")"
      rm -f "$src/$f"
      cp -P --preserve=mode "$root/$f" "$src/$f" || die "cannot copy $f"
      copied=$((copied + 1))
    fi
  done < <(git -C "$root" ls-files -z --cached --others --exclude-standard)
  while IFS= read -r -d '' f; do
    f="${f#"$src"/}"
    if [ -z "${listed[$f]+x}" ]; then rm -f "$src/$f"; removed=$((removed + 1)); fi
  done < <(find "$src" \( -type f -o -type l \) -print0)
  echo "scratch tree: ${#listed[@]} files, $copied copied, $removed removed"
}
sync_tree

export CCACHE_BASEDIR="$work" CCACHE_NOHASHDIR=true
if [ ! -f "$build/CMakeCache.txt" ]; then
  launcher=()
  if command -v ccache >/dev/null 2>&1; then
    launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  fi
  echo "configuring $build"
  cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
    -DAPCI_BUILD_BENCH=OFF -DAPCI_WERROR=ON > "$logs/configure.log" 2>&1 || die "configure failed: $logs/configure.log"
fi

# ---- Running test programs

# run_program PROGRAM FILTER LOG: runs one test program with the time limit. Sets RUN_RESULT
# (pass, fail, crash, timeout, none: no test ran), RUN_TEST (the first failing or interrupted
# test) and RUN_FAILED (the failing tests, one per line).
run_program() {
  local program=$1 filter=$2 log=$3 rc
  local args=()
  [ -n "$filter" ] && args+=("--gtest_filter=$filter")
  RUN_RESULT="" RUN_TEST="" RUN_FAILED=""
  if [ ! -x "$build/bin/$program" ]; then
    RUN_RESULT="missing"
    return
  fi
  (cd "$build" && timeout --kill-after=10 "$timeout_s" "bin/$program" "${args[@]}") > "$log" 2>&1
  rc=$?
  RUN_FAILED="$(sed -n 's/^\[  FAILED  \] \([A-Za-z0-9_/]*\.[A-Za-z0-9_/.]*\).*/\1/p' "$log" | awk '!seen[$0]++')"
  local last_run
  last_run="$(sed -n 's/^\[ RUN      \] \(.*\)$/\1/p' "$log" | tail -n 1)"
  if [ $rc -eq 124 ] || [ $rc -eq 137 ]; then
    RUN_RESULT="timeout"; RUN_TEST="$last_run"
  elif [ $rc -gt 128 ]; then
    RUN_RESULT="crash"; RUN_TEST="$last_run"
  elif [ $rc -ne 0 ]; then
    if [ -n "$RUN_FAILED" ]; then
      RUN_RESULT="fail"; RUN_TEST="$(head -n 1 <<< "$RUN_FAILED")"
    else
      RUN_RESULT="crash"; RUN_TEST="${last_run:-$program (exit $rc)}"
    fi
  elif grep -q '^\[==========\] 0 tests from' "$log" || ! grep -q '^\[  PASSED  \]' "$log"; then
    RUN_RESULT="none"
  else
    RUN_RESULT="pass"
  fi
}

# run_ctest REGEX LOG: runs the CTest tests whose names match REGEX (a script's test, such as
# a Python one, is no GoogleTest program), each with the time limit; the tests that failed on
# the unmutated tree are left out. Sets RUN_RESULT, RUN_TEST and RUN_FAILED as run_program.
run_ctest() {
  local regex=$1 log=$2 rc
  local args=(-R "$regex" --output-on-failure --timeout "$timeout_s")
  [ -n "${EXCLUDED[ctest=$regex]:-}" ] && args+=(-E "^(${EXCLUDED[ctest=$regex]})\$")
  RUN_RESULT="" RUN_TEST="" RUN_FAILED=""
  if [ -z "$regex" ]; then RUN_RESULT="none"; return; fi
  (cd "$build" && ctest "${args[@]}") > "$log" 2>&1
  rc=$?
  # "The following tests FAILED:" then one "  N - NAME (Failed|Timeout|SEGFAULT|...)" a test.
  RUN_FAILED="$(sed -n '/^The following tests FAILED:/,$s/^[[:space:]]*[0-9][0-9]* - \([^ ]*\) (.*$/\1/p' "$log")"
  RUN_TEST="$(head -n 1 <<< "$RUN_FAILED")"
  if grep -q '^No tests were found' "$log"; then
    RUN_RESULT="none"
  elif [ $rc -eq 0 ]; then
    RUN_RESULT="pass"
  elif [ -z "$RUN_FAILED" ]; then
    RUN_RESULT="crash"; RUN_TEST="ctest (exit $rc)"
  elif grep -q "^[[:space:]]*[0-9][0-9]* - $RUN_TEST (Timeout)" "$log"; then
    RUN_RESULT="timeout"
  else
    RUN_RESULT="fail"
  fi
}

# The gtest filter of FILTER without the tests that fail on the unmutated tree.
declare -A EXCLUDED=()
with_exclusions() {
  local program=$1 filter=$2
  local ex="${EXCLUDED[$program]:-}"
  [ -z "$ex" ] && { printf '%s' "$filter"; return; }
  [ -z "$filter" ] && filter="*"
  if [[ "$filter" == *-* ]]; then printf '%s:%s' "$filter" "$ex"; else printf '%s-%s' "$filter" "$ex"; fi
}

build_targets() {  # build_targets LOG TARGET... (none: nothing to build)
  local log=$1
  shift
  [ $# -gt 0 ] || { echo "nothing to build" > "$log"; return 0; }
  cmake --build "$build" -j"$jobs" --target "$@" > "$log" 2>&1
}

# ---- Baseline: the unmutated tree builds and its tests pass

declare -A all_targets=() all_programs=()
for i in "${SEL[@]}"; do
  for t in ${M_BUILD[$i]}; do all_targets[$t]=1; done
  for spec in ${M_RUN[$i]}; do
    # A CTest selection is run (and its failures left out) as written, a program as a whole.
    if [ "${spec%%=*}" = ctest ]; then all_programs[$spec]=1; else all_programs[${spec%%=*}]=1; fi
  done
done
echo "baseline: building ${!all_targets[*]}"
build_targets "$logs/baseline.build.log" "${!all_targets[@]}" ||
  die "the unmutated tree does not build: $logs/baseline.build.log"
baseline_notes=()
baseline_n=0
for program in "${!all_programs[@]}"; do
  if [ "${program%%=*}" = ctest ]; then
    baseline_n=$((baseline_n + 1))
    baseline_log="$logs/baseline.ctest-$baseline_n.log"
    run_ctest "${program#ctest=}" "$baseline_log"
  else
    baseline_log="$logs/baseline.$program.log"
    run_program "$program" "" "$baseline_log"
  fi
  case "$RUN_RESULT" in
    pass) ;;
    fail)
      # Tests that fail without any mutant cannot tell a mutant apart: left out, with a note.
      if [ "${program%%=*}" = ctest ]; then
        EXCLUDED[$program]="$(paste -sd'|' <<< "$RUN_FAILED" | sed 's/\./\\./g')"
      else
        EXCLUDED[$program]="$(paste -sd: <<< "$RUN_FAILED")"
      fi
      while IFS= read -r t; do
        baseline_notes+=("$program: $t fails on the unmutated tree: left out")
        echo "warning: $program: $t fails on the unmutated tree: left out" >&2
      done <<< "$RUN_FAILED"
      ;;
    *) die "baseline: $program: $RUN_RESULT ${RUN_TEST:-} ($baseline_log)" ;;
  esac
done

# ---- The mutants

applied_path="" applied_backup=""
restore() {
  if [ -n "$applied_path" ]; then
    # A plain copy: the file gets a new modification time, so the next build recompiles it
    # (ccache makes that cheap).
    cp "$applied_backup" "$applied_path"
    applied_path=""
  fi
}
trap 'restore' EXIT
trap 'restore; exit 130' INT TERM

V_WHERE=() V_VERDICT=() V_BY=() V_SECONDS=()
killed=0 survived=0 equivalent=0 compiler=0 errors=0
n=0
for i in "${SEL[@]}"; do
  n=$((n + 1))
  t0=$(date +%s)
  id="${M_ID[$i]}"
  verdict="" by=""
  if ! locate "$i" "$src"; then
    V_WHERE[i]="${M_FILE[$i]}"
    verdict="error"; by="$WHY"
  else
    V_WHERE[i]="$WHERE"
    path="$src/${M_FILE[$i]}"
    read_file "$path" text
    applied_backup="$work/original.tmp"
    cp "$path" "$applied_backup"
    applied_path="$path"
    printf '%s' "${text/"${M_FROM[$i]}"/"${M_TO[$i]}"}" > "$path"
    # shellcheck disable=SC2086
    if ! build_targets "$logs/$id.build.log" ${M_BUILD[$i]}; then
      verdict="compiler"; by="does not build: logs/$id.build.log"
    else
      verdict="survived"
      for spec in ${M_RUN[$i]}; do
        program="${spec%%=*}"
        filter=""
        [[ "$spec" == *=* ]] && filter="${spec#*=}"
        if [ "$program" = ctest ]; then
          run_ctest "$filter" "$logs/$id.ctest.log"
        else
          run_program "$program" "$(with_exclusions "$program" "$filter")" "$logs/$id.$program.log"
        fi
        case "$RUN_RESULT" in
          pass) ;;
          fail)
            verdict="killed"
            more=$(($(wc -l <<< "$RUN_FAILED") - 1))
            by="$program: $RUN_TEST"
            [ "$more" -gt 0 ] && by+=" (+$more)"
            break ;;
          crash) verdict="killed"; by="$program: crash in $RUN_TEST"; break ;;
          timeout) verdict="killed"; by="$program: timeout in $RUN_TEST"; break ;;
          none) verdict="error"; by="$program: no test matches '${filter:-*}'"; break ;;
          missing) verdict="error"; by="$program: no such program (built: ${M_BUILD[$i]})"; break ;;
        esac
      done
    fi
    restore
  fi
  # A mutant shown to behave as the original (its `equivalent:` says why) cannot be killed;
  # if a test kills it after all, the mark is wrong.
  if [ -n "${M_EQUIV[$i]}" ]; then
    case "$verdict" in
      survived) verdict="equivalent"; by="${M_EQUIV[$i]}" ;;
      killed) verdict="error"; by="marked equivalent, but killed by $by" ;;
    esac
  fi
  case "$verdict" in
    killed) killed=$((killed + 1)) ;;
    survived) survived=$((survived + 1)) ;;
    equivalent) equivalent=$((equivalent + 1)) ;;
    compiler) compiler=$((compiler + 1)) ;;
    *) errors=$((errors + 1)) ;;
  esac
  V_VERDICT[i]="$verdict"
  V_BY[i]="$by"
  V_SECONDS[i]=$(($(date +%s) - t0))
  printf '[%d/%d] %-34s %-9s %s (%ds)\n' "$n" "${#SEL[@]}" "$id" "$verdict" "$by" "${V_SECONDS[$i]}"
done
rm -f "$work/original.tmp"

# ---- The report

elapsed=$(($(date +%s) - started))
summary="${#SEL[@]} mutants, $killed killed, $survived survived"
[ "$equivalent" -gt 0 ] && summary+=", $equivalent equivalent"
[ "$compiler" -gt 0 ] && summary+=", $compiler killed by the compiler"
[ "$errors" -gt 0 ] && summary+=", $errors errors"
duration="$((elapsed / 60)) min $((elapsed % 60)) s"

echo
printf '%-34s %-44s %-9s %s\n' "id" "file:line" "verdict" "description / killed by"
for i in "${SEL[@]}"; do
  printf '%-34s %-44s %-9s %s\n' "${M_ID[$i]}" "${V_WHERE[$i]}" "${V_VERDICT[$i]}" "${M_ABOUT[$i]}"
  [ -n "${V_BY[$i]}" ] && printf '%-34s %-44s %-9s   %s\n' "" "" "" "${V_BY[$i]}"
done
for note in "${baseline_notes[@]}"; do echo "note: $note"; done
echo "$summary ($duration)"

{
  echo "| id | file:line | description | verdict | killed by |"
  echo "|---|---|---|---|---|"
  for i in "${SEL[@]}"; do
    # shellcheck disable=SC2016  # the backquotes are Markdown
    printf '| `%s` | %s | %s | %s | %s |\n' "${M_ID[$i]}" "${V_WHERE[$i]}" "${M_ABOUT[$i]}" \
      "${V_VERDICT[$i]}" "${V_BY[$i]:+\`${V_BY[$i]}\`}"
  done
  echo
  for note in "${baseline_notes[@]}"; do echo "Note: $note."; done
  echo "$summary ($duration)."
} > "$work/report.md"
echo "report: $work/report.md"

if [ "$survived" -gt 0 ]; then exit 1; fi
if [ "$compiler" -gt 0 ] || [ "$errors" -gt 0 ]; then exit 2; fi
exit 0
