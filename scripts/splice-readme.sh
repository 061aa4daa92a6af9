#!/usr/bin/env bash
# scripts/splice-readme.sh NAME FILE [README]
#
# Replaces the lines between `<!-- NAME:begin -->` and `<!-- NAME:end -->`
# of README (default: the repository's README.md) with the contents of
# FILE, e.g. the table an example wrote:
#
#   cargo run --release --example stability_sweep
#   scripts/splice-readme.sh stability-faces docs/stability/stability-faces.md
#
# Fails, leaving README untouched, when either marker is missing.
set -euo pipefail
name=$1
file=$2
readme=${3:-"$(dirname "$0")/../README.md"}
begin="<!-- $name:begin -->"
end="<!-- $name:end -->"
grep -qxF -- "$begin" "$readme" || { echo "splice-readme: no '$begin' in $readme" >&2; exit 1; }
grep -qxF -- "$end" "$readme" || { echo "splice-readme: no '$end' in $readme" >&2; exit 1; }
[ -r "$file" ] || { echo "splice-readme: cannot read $file" >&2; exit 1; }
awk -v b="$begin" -v e="$end" -v f="$file" '
  $0 == b { print; while ((getline line < f) > 0) print line; skip = 1; next }
  $0 == e { skip = 0 }
  !skip { print }' "$readme" > "$readme.tmp"
mv "$readme.tmp" "$readme"
