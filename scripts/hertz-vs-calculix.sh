#!/usr/bin/env bash
# gapsim against CalculiX on the Hertz quarter model (issue #10 §2), in one
# run on this machine; writes docs/hertz/hertz-vs-calculix.{md,csv} and
# prints the table.
#
#   scripts/hertz-vs-calculix.sh [REPEAT]      # default 3: medians of 3 runs
#
# 1. CalculiX (scripts/calculix-hertz.py): the checked-in mesh
#    scenes/hertz.msh as a CPE4 deck with penalty contact, `ccx` run REPEAT
#    times as a whole process with OMP_NUM_THREADS=2 (work files in
#    target/calculix-hertz/, its JSON in target/calculix-hertz.json).
# 2. gapsim (examples/hertz_vs_calculix.rs, release build): scenes/hertz.toml
#    (finite strain) and scenes/hertz-small-strain.toml with --linear lu and
#    ldlt, REPEAT times each, with RAYON_NUM_THREADS=2; scene and mesh
#    reading plus the solve, in-process.
#
# Needs `ccx` (Debian: apt-get install calculix-ccx) and python3 (no extra
# packages): a benchmark, never part of the test suite. Takes about
# 3 x 40 s for CalculiX on a 2-core machine plus half a minute for gapsim.
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-3}

command -v ccx > /dev/null || { echo "hertz-vs-calculix: ccx not found (apt-get install calculix-ccx)" >&2; exit 1; }
cargo build -q --release --example hertz_vs_calculix

python3 scripts/calculix-hertz.py --repeat "$repeat" --threads 2 > target/calculix-hertz.json.tmp
mv target/calculix-hertz.json.tmp target/calculix-hertz.json

RAYON_NUM_THREADS=2 target/release/examples/hertz_vs_calculix \
  --calculix target/calculix-hertz.json --repeat "$repeat" --out docs/hertz
