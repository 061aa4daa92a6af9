#!/usr/bin/env bash
# The linear solvers on scenes/pressed-block3d.toml refined r-fold: one
# whole `gapsim run` per (r, solver[, MPI ranks]), its equations, energy,
# Newton iterations, linear-solve time, Krylov iterations and peak memory
# (/usr/bin/time's maximum resident set size: across ranks, that of the
# largest process), as a markdown table.
#
#   scripts/petsc-scaling.sh "4:ldlt 4:petsc 4:petsc:2 6:petsc" > docs/petsc/scaling.md
#
# Needs a gapsim built with the petsc feature (target/release/gapsim, built
# here when missing), GNU time, and for runs across ranks mpiexec (Open MPI;
# as root it needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1).
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-"4:ldlt 4:petsc"}
bin=target/release/gapsim
[ -x "$bin" ] || cargo build --release --features petsc >&2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "One load step of scenes/pressed-block3d.toml refined r-fold (\`[refine] x = y = z = r\`), \`gapsim run --linear SOLVER\` (across ranks under \`mpiexec -n RANKS\`); one run each, $(nproc) cores; peak: maximum resident set size of the run's largest process (across ranks, the largest rank's)."
echo
echo "| r | solver | ranks | equations | strain energy | Newton iterations | linear solve s | Krylov iterations per solve (max) | total s | peak MiB |"
echo "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for run in $runs; do
  IFS=: read -r r solver ranks <<< "$run"
  ranks=${ranks:-1}
  launch=()
  [ "$ranks" -gt 1 ] && launch=(mpiexec -n "$ranks")
  scene="$tmp/pressed-block3d-r$r.toml"
  printf '\n[refine]\nx = %d\ny = %d\nz = %d\n' "$r" "$r" "$r" | cat scenes/pressed-block3d.toml - > "$scene"
  out="$tmp/out-$r-$solver-$ranks.txt"
  /usr/bin/time -v "${launch[@]}" "$bin" run "$scene" --linear "$solver" > "$out" 2>&1
  eq=$(awk '/^equations/ {print $2}' "$out")
  energy=$(awk '/^strain energy/ {print $3}' "$out")
  newton=$(awk '/^Newton/ {print $2}' "$out")
  total=$(sed -n 's/^time *\([0-9.]*\) ms.*/\1/p' "$out")
  lin=$(sed -n 's/.*linear solve \([0-9.]*\)).*/\1/p' "$out")
  krylov=$(sed -n 's/^krylov.*, \([0-9.]*\) per solve, at most \([0-9]*\)).*/\1 (\2)/p' "$out")
  peak=$(awk -F: '/Maximum resident/ {gsub(/ /, "", $2); print $2}' "$out")
  printf '| %s | %s | %s | %s | %s | %s | %.1f | %s | %.1f | %d |\n' "$r" "$solver" "$ranks" "$eq" "$energy" "$newton" \
    "$(echo "$lin / 1000" | bc -l)" "${krylov:--}" "$(echo "$total / 1000" | bc -l)" "$((peak / 1024))"
done
