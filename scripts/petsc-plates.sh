#!/usr/bin/env bash
# The PETSc default on plates in persistent contact bending along their
# length (docs/petsc.md, "Where the multigrid does not converge"): each
# scene run with `--linear petsc` and `--linear ldlt`, one run each, its
# strain energy, Newton iterations, time, peak resident memory and the
# PETSc run's `krylov` line; a markdown table.
#
#   scripts/petsc-plates.sh > docs/petsc/petsc-plates.md
#   scripts/splice-docs.sh petsc-plates docs/petsc/petsc-plates.md docs/petsc.md
#
# The scenes: the 3D paper scene, the 2D paper scene refined 16 x 64, and
# the contact-heavy 3D scene of the types' pay-off (SCENES overrides, each
# `FILE` or `FILE:REFINE_X:REFINE_Y`). Uses target/release/gapsim, built
# here with `--features petsc`; /usr/bin/time for the peak.
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${SCENES:-"scenes/stacked-plates.toml scenes/stacked-cantilever.toml:16:64 scenes/stacked-plates-heavy.toml"}
bin=target/release/gapsim
cargo build -q --release --features petsc >&2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "\`gapsim run SCENE --linear SOLVER\` (the scene's own steps and method), one run each, in the order of the table, $(nproc) cores; peak: maximum resident set size."
echo
echo "| scene | equations | solver | strain energy | Newton iterations | total s | linear solve s | peak MiB | Krylov |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---|"
for spec in $scenes; do
  IFS=: read -r file rx ry <<< "$spec"
  name=$(basename "$file" .toml)
  scene=$file
  if [ -n "${rx:-}" ]; then
    name="$name, refined $rx x $ry"
    scene="$tmp/$(basename "$file" .toml)-$rx-$ry.toml"
    # the scene's own folder holds what it names
    cp "$file" "$scene"
    printf '\n[refine]\nx = %s\ny = %s\n' "$rx" "$ry" >> "$scene"
  fi
  for linear in petsc ldlt; do
    out="$tmp/out.txt"
    if ! /usr/bin/time -f 'peak %M' "$bin" run "$scene" --linear "$linear" > "$out" 2>&1; then
      echo "| $name | - | $linear | failed: $(grep -v '^peak' "$out" | tail -n 1) |"
      continue
    fi
    eqs=$(awk '/^equations/ {print $2}' "$out")
    energy=$(awk '/^strain energy/ {print $3}' "$out")
    newton=$(awk '/^Newton/ {print $2}' "$out")
    total=$(sed -n 's/^time *\([0-9.]*\) ms.*/\1/p' "$out")
    lin=$(sed -n 's/.*linear solve \([0-9.]*\)).*/\1/p' "$out")
    peak=$(awk '/^peak/ {print $2}' "$out")
    krylov=$(sed -n 's/^krylov *//p' "$out")
    printf '| %s | %s | %s | %s | %s | %.1f | %.1f | %d | %s |\n' "$name" "$eqs" "$linear" "$energy" "$newton" \
      "$(echo "$total / 1000" | bc -l)" "$(echo "$lin / 1000" | bc -l)" "$((peak / 1024))" "${krylov:--}"
  done
done
