#!/usr/bin/env bash
# Shows that a change left every result as it was:
#  1. reruns the study (release build) into target/unchanged/study and
#     compares its CSV files with the committed ones in docs/study, every
#     column but the timings, value for value;
#  2. reruns `gapsim kernel` on a fixed set of configurations (both
#     formulations, every type, degenerate input) and compares the output
#     with scripts/baseline/kernel-outputs.txt;
#  3. reruns the 3D study on scenes/stacked-plates.toml (4 and 8 steps) and
#     compares it with scripts/baseline/study3d (timings aside);
#  4. runs `gapsim run --out` on the 3D scenes (scenes/hertz3d.toml on its
#     hexahedral and tetrahedral meshes with the LDLᵀ, sliding3d,
#     patch-test3d, cantilever3d) and on the 2D paper scene, and compares
#     the SHA-256 of every file written (final.vtu, contact.csv,
#     reactions.csv, and the printed summary without its timings) with
#     scripts/baseline/run-outputs.sha256.
# Run it before regenerating docs/study. A deliberate change of results
# re-records the baselines: `scripts/check-unchanged.sh --bless` (it also
# rewrites docs/study's CSV files only through the study command itself:
# `gapsim study --out docs/study`).
set -euo pipefail
cd "$(dirname "$0")/.."
bless=0
[ "${1:-}" = "--bless" ] && bless=1

cargo build -q --release --bin gapsim
bin=target/release/gapsim
out=target/unchanged
rm -rf "$out"; mkdir -p "$out"
status=0

# 1. the 2D study
$bin study --out "$out/study" > "$out/study.log" 2>&1
scripts/compare-study.sh docs/study "$out/study" || status=1

# 2. the kernels
scripts/kernel-outputs.sh $bin > "$out/kernel-outputs.txt"
if [ $bless = 1 ]; then
  cp "$out/kernel-outputs.txt" scripts/baseline/kernel-outputs.txt
fi
if diff -u scripts/baseline/kernel-outputs.txt "$out/kernel-outputs.txt" > "$out/kernel-outputs.diff"; then
  echo "identical: gapsim kernel output ($(grep -c '^==' "$out/kernel-outputs.txt") evaluations)"
else
  echo "DIFFERENT: gapsim kernel output (see $out/kernel-outputs.diff)"; status=1
fi

# 3. the 3D study
$bin study scenes/stacked-plates.toml --repeats 1 --steps 4,8 --out "$out/study3d" \
  > "$out/study3d.log" 2>&1
if [ $bless = 1 ]; then
  rm -rf scripts/baseline/study3d; mkdir -p scripts/baseline/study3d
  cp "$out"/study3d/*.csv scripts/baseline/study3d/
fi
scripts/compare-study.sh scripts/baseline/study3d "$out/study3d" || status=1

# 4. the runs: NAME then the arguments of `gapsim run`
runs=(
  "paper2d|--steps 4 --type 3"
  "hertz3d-hex|scenes/hertz3d.toml --linear ldlt --steps 2"
  "hertz3d-tet|$out/hertz3d-tet.toml --linear ldlt --steps 2"
  "sliding3d|scenes/sliding3d.toml --steps 20"
  "sliding3d-type3|scenes/sliding3d.toml --steps 20 --type 3"
  "patch-test3d|scenes/patch-test3d.toml"
  "cantilever3d|scenes/cantilever3d.toml"
)
sed 's/hertz3d-hex\.msh/hertz3d-tet.msh/' scenes/hertz3d.toml > "$out/hertz3d-tet.toml"
cp scenes/hertz3d-tet.msh "$out/"
sums="$out/run-outputs.sha256"
: > "$sums"
for r in "${runs[@]}"; do
  name=${r%%|*}
  args=${r#*|}
  # shellcheck disable=SC2086 # the arguments are words
  if ! $bin run $args --out "$out/runs/$name" > "$out/$name.out" 2> "$out/$name.err"; then
    echo "FAILED: gapsim run $args (see $out/$name.err)"; status=1; continue
  fi
  # the printed summary without its timings
  grep -v '^time \|^factorisation ' "$out/$name.out" > "$out/runs/$name/summary.txt"
  (cd "$out/runs" && sha256sum "$name"/*) >> "$sums"
done
if [ $bless = 1 ]; then
  cp "$sums" scripts/baseline/run-outputs.sha256
fi
if diff -u scripts/baseline/run-outputs.sha256 "$sums" > "$out/run-outputs.diff"; then
  echo "identical: gapsim run outputs ($(wc -l < "$sums") files of ${#runs[@]} runs)"
else
  echo "DIFFERENT: gapsim run outputs (see $out/run-outputs.diff)"; status=1
fi
exit $status
