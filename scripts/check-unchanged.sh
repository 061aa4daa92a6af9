#!/usr/bin/env bash
# Shows that a change left every result as it was:
#  1. reruns the study (release build) into target/unchanged/study and
#     compares its CSV files with the committed ones in docs/study, every
#     column but the timings, value for value;
#  2. reruns `gapsim kernel` on a fixed set of configurations (both
#     formulations, every type, degenerate input) and compares the output
#     with scripts/baseline/kernel-outputs.txt.
# Run it before regenerating docs/study. A deliberate change of results
# re-records the baseline: `scripts/kernel-outputs.sh target/release/gapsim >
# scripts/baseline/kernel-outputs.txt` and a new study in docs/study.
set -euo pipefail
cd "$(dirname "$0")/.."

cargo build -q --release --bin gapsim
out=target/unchanged
rm -rf "$out"; mkdir -p "$out"
target/release/gapsim study --out "$out/study" > "$out/study.log" 2>&1
status=0
scripts/compare-study.sh docs/study "$out/study" || status=1

scripts/kernel-outputs.sh target/release/gapsim > "$out/kernel-outputs.txt"
if diff -u scripts/baseline/kernel-outputs.txt "$out/kernel-outputs.txt" > "$out/kernel-outputs.diff"; then
  echo "identical: gapsim kernel output ($(grep -c '^==' "$out/kernel-outputs.txt") evaluations)"
else
  echo "DIFFERENT: gapsim kernel output (see $out/kernel-outputs.diff)"; status=1
fi
exit $status
