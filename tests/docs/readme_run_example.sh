#!/bin/sh
# SPDX-License-Identifier: MIT
# README's `apcictl run` example, exactly as printed there (the indented lines from the one
# that starts "mkdir -p out" through the `apcictl run` line and its continuation), run in a
# fresh directory that holds only build/bin/apcictl and examples/, as a reader's checkout
# before ./run.sh made out/: it must succeed and write the files it names.
#   readme_run_example.sh SOURCE_DIR APCICTL
set -eu
source_dir=$1
apcictl=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/build/bin"
ln -s "$apcictl" "$work/build/bin/apcictl"
ln -s "$source_dir/examples" "$work/examples"
# The example block: from the first indented line naming out/ up to the line without a
# trailing backslash after the `apcictl run` line.
sed -n '/^    mkdir -p out$/,/^    .*--svg out\/.*[^\\]$/p' "$source_dir/README.md" | sed 's/^    //' \
  > "$work/example.sh"
grep -q 'apcictl run' "$work/example.sh" || { echo "README: the run example was not found" >&2; exit 1; }
cat "$work/example.sh"
(cd "$work" && sh -e example.sh >/dev/null)
for f in out/wr_quad_disc.svg out/wr_quad_disc.json; do
  test -s "$work/$f" || { echo "README's example wrote no $f" >&2; exit 1; }
done
echo "README's run example: ok"
