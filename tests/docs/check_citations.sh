#!/bin/sh
# SPDX-License-Identifier: MIT
# Keeps the repository standing on its own (docs/references.md):
#   check_citations.sh outside SOURCE_DIR
#     fails, listing file:line, where any text file cites the outside design briefing by its
#     file name, a source document by its file or number (the "seeds" of that briefing), or a
#     path into a directory beside the repository;
#   check_citations.sh keys SOURCE_DIR
#     fails, listing file:line, where a reference key in square brackets ("[APCI-TC]": capitals,
#     digits and at least one hyphen, or a key listed in docs/references.md) names no entry
#     ("## [KEY]") of docs/references.md.
# Both search every file under SOURCE_DIR except .git and build directories (build*), skipping
# binary files; each is one grep over the tree.
# The patterns below are spelled so that they do not match this file itself.
set -u
mode="${1:-}"
src="${2:-}"
if [ -z "$mode" ] || [ -z "$src" ] || [ ! -d "$src" ]; then
  echo "usage: check_citations.sh outside|keys SOURCE_DIR" >&2
  exit 2
fi
cd "$src" || exit 2
search() {
  grep -rnIE --exclude-dir=.git --exclude-dir='build*' --exclude=.git "$@" .
}

case "$mode" in
outside)
  # The briefing's file name (upper case: docs/design.md is ours); the source documents by
  # their folder or number (the word seed, any case, then a digit, with or without a space) or
  # cited as "the seed" (that word after an opening parenthesis, or before document, section,
  # table, example, ...; the fuzzers' seed corpus and the random generators' seeds are not
  # citations and do not match); paths into the folder beside the repository that held them.
  pattern='DESIGN[.]md|DESIGN (§|section)|seed[s]/|[Ss][Ee][Ee][Dd] ?[0-9]'
  pattern="$pattern|[.][.]/shared|/work/share[d]"
  pattern="$pattern|[(][Ss]eed([ :,]|\$)|[Ss]eeds? (document|section|table|TC|text)"
  pattern="$pattern|[Tt]he seeds?('s?)? (document|text|section|table|example|program|name)"
  hits="$(search -e "$pattern")"
  if [ -n "$hits" ]; then
    printf '%s\n' "$hits"
    n="$(printf '%s\n' "$hits" | wc -l)"
    echo "$n line(s) cite a document outside the repository: cite it by its key in" \
      "docs/references.md and its own section (\"[APCI-TC] Table 2\"), or docs/design.md" >&2
    exit 1
  fi
  echo "no citation leaves the repository"
  ;;
keys)
  refs=docs/references.md
  if [ ! -f "$refs" ]; then
    echo "$refs is missing" >&2
    exit 1
  fi
  defined="$(sed -n 's/^## \[\([^]]*\)\].*$/\1/p' "$refs")"
  if [ -z "$defined" ]; then
    echo "$refs defines no key (no '## [KEY]' heading)" >&2
    exit 1
  fi
  # Keys without a hyphen (such as [LinuxCNC]) are found by their exact names.
  extra="$(printf '%s\n' "$defined" | grep -v -e - | sed 's/.*/\\[&\\]/' | paste -sd'|' -)"
  pattern='\[[A-Z][A-Z0-9]+(-[A-Z0-9]+)+\]'
  [ -n "$extra" ] && pattern="$pattern|$extra"
  tmp="${TMPDIR:-/tmp}/apci_keys.$$"
  trap 'rm -f "$tmp.defined" "$tmp.cited"' EXIT
  printf '%s\n' "$defined" >"$tmp.defined"
  search -o -e "$pattern" >"$tmp.cited"
  # Each cited line is ./FILE:LINE:[KEY]; report those whose KEY is not defined.
  unknown="$(awk -v refs="$refs" '
    NR == FNR { known[$0] = 1; next }
    { key = $0; sub(/^.*:\[/, "", key); sub(/\]$/, "", key)
      at = $0; sub(/\[[^[]*$/, "", at)
      if (!(key in known)) print at " [" key "] has no entry in " refs }' \
    "$tmp.defined" "$tmp.cited")"
  cited="$(wc -l <"$tmp.cited")"
  if [ -n "$unknown" ]; then
    printf '%s\n' "$unknown"
    echo "$(printf '%s\n' "$unknown" | wc -l) citation(s) of keys that $refs does not list:" \
      "add a section '## [KEY]' for the document there (title, publisher, edition)" \
      "or correct the key" >&2
    exit 1
  fi
  echo "every cited key ($cited citations) is listed in $refs"
  ;;
*)
  echo "check_citations.sh: unknown mode '$mode' (outside or keys)" >&2
  exit 2
  ;;
esac
