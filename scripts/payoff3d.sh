#!/usr/bin/env bash
# The pay-off of the approximation types on a contact-heavy 3D scene of
# 1.07e5 equations (scenes/stacked-plates-heavy.toml, 128000 slave
# integration points): one whole `gapsim run` per (method, steps), in the
# order given, its strain energy, Newton iterations and time split, and
# against the complete formulation at the same step count (which must come
# first in the list) the energy error and the time ratios; a markdown table.
#
#   scripts/payoff3d.sh "complete:4 3:4 6:4 complete:8 3:8 6:8" > docs/payoff3d/payoff3d.md
#
# Uses target/release/gapsim (built here when missing) and the scene's
# linear solver (the LDLᵀ); a second argument picks another (`petsc`, in a
# build with the feature).
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-"complete:4 3:4"}
linear=${2:-ldlt}
scene=scenes/stacked-plates-heavy.toml
bin=target/release/gapsim
[ -x "$bin" ] || cargo build --release >&2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "\`gapsim run $scene --type METHOD --steps STEPS --linear $linear\`: one run each, in the order of the table, $(nproc) cores; error: 100 (U - U_complete) / U_complete at the same step count; ratios to the complete formulation's run at the same step count."
echo
echo "| method | steps | strain energy | error % | Newton iterations | total s | contact s | linear solve s | solve share | total / complete | contact / complete |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
declare -A ref_energy ref_total ref_contact
for run in $runs; do
  IFS=: read -r method steps <<< "$run"
  out="$tmp/out-$method-$steps.txt"
  "$bin" run "$scene" --type "$method" --steps "$steps" --linear "$linear" > "$out" 2>&1 || {
    echo "| $method | $steps | failed: $(tail -n 1 "$out") |"
    continue
  }
  energy=$(awk '/^strain energy/ {print $3}' "$out")
  newton=$(awk '/^Newton/ {print $2}' "$out")
  total=$(sed -n 's/^time *\([0-9.]*\) ms.*/\1/p' "$out")
  contact=$(sed -n 's/.*contact \([0-9.]*\),.*/\1/p' "$out")
  lin=$(sed -n 's/.*linear solve \([0-9.]*\)).*/\1/p' "$out")
  if [ "$method" = complete ]; then
    ref_energy[$steps]=$energy ref_total[$steps]=$total ref_contact[$steps]=$contact
  fi
  err=- rt=- rc=-
  if [ -n "${ref_energy[$steps]:-}" ]; then
    err=$(printf '%+.2e' "$(echo "100 * ($energy - ${ref_energy[$steps]}) / ${ref_energy[$steps]}" | bc -l)")
    rt=$(printf '%.2f' "$(echo "$total / ${ref_total[$steps]}" | bc -l)")
    rc=$(printf '%.2f' "$(echo "$contact / ${ref_contact[$steps]}" | bc -l)")
  fi
  printf '| %s | %s | %s | %s | %s | %.1f | %.1f | %.1f | %.2f | %s | %s |\n' "$method" "$steps" "$energy" "$err" "$newton" \
    "$(echo "$total / 1000" | bc -l)" "$(echo "$contact / 1000" | bc -l)" "$(echo "$lin / 1000" | bc -l)" \
    "$(echo "$lin / $total" | bc -l)" "$rt" "$rc"
done
