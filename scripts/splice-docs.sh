#!/usr/bin/env bash
# scripts/splice-docs.sh NAME FILE PAGE
#
# Replaces the lines between `<!-- NAME:begin -->` and `<!-- NAME:end -->`
# of PAGE (the docs page that holds that marker, e.g. docs/kernels.md) with
# the contents of FILE, e.g. the table an example wrote:
#
#   cargo run --release --example stability_sweep
#   scripts/splice-docs.sh stability-faces docs/stability/stability-faces.md docs/kernels.md
#
# The pages and their markers: docs/kernels.md (stability, stability-faces,
# bench, bench-faces), docs/solver.md (scaling, scaling3d),
# docs/petsc.md (petsc-plates), docs/benchmarks.md (hertz, patch, calculix, safety-map,
# hertz3d-refinement, calculix3d), docs/study.md (study, which
# `gapsim study --readme docs/study.md` splices itself).
#
# Fails, leaving PAGE untouched, when either marker is missing.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: splice-docs.sh NAME FILE PAGE" >&2
  exit 2
fi
name=$1
file=$2
page=$3
begin="<!-- $name:begin -->"
end="<!-- $name:end -->"
grep -qxF -- "$begin" "$page" || { echo "splice-docs: no '$begin' in $page" >&2; exit 1; }
grep -qxF -- "$end" "$page" || { echo "splice-docs: no '$end' in $page" >&2; exit 1; }
[ -r "$file" ] || { echo "splice-docs: cannot read $file" >&2; exit 1; }
awk -v b="$begin" -v e="$end" -v f="$file" '
  $0 == b { print; while ((getline line < f) > 0) print line; skip = 1; next }
  $0 == e { skip = 0 }
  !skip { print }' "$page" > "$page.tmp"
mv "$page.tmp" "$page"
