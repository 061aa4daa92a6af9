#!/usr/bin/env bash
# gapsim against CalculiX on the 3D Hertz quarter model (issue #17 §4), in
# one run on this machine; writes docs/hertz3d/hertz3d-vs-calculix.{md,csv}
# and prints the table.
#
#   scripts/hertz3d-vs-calculix.sh [REPEAT]    # default 1: one run each
#
# 1. CalculiX (scripts/calculix-hertz3d.py): the checked-in mesh
#    scenes/hertz3d-hex.msh as a C3D8 deck with penalty contact, `ccx` run
#    REPEAT times as a whole process with OMP_NUM_THREADS=2 (work files in
#    target/calculix-hertz3d/, its JSON in target/calculix-hertz3d.json).
# 2. gapsim (examples/hertz3d_vs_calculix.rs, release build):
#    scenes/hertz3d.toml with --linear ldlt, REPEAT times, with
#    RAYON_NUM_THREADS=2; scene and mesh reading plus the solve, in-process.
#
# Needs `ccx` (Debian: apt-get install calculix-ccx) and python3 with the
# `gmsh` package (pip install gmsh, to read the binary mesh): a benchmark,
# never part of the test suite. One CalculiX run takes many minutes on a
# 2-core machine (hence REPEAT 1 by default), gapsim's under a minute.
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-1}

command -v ccx > /dev/null || { echo "hertz3d-vs-calculix: ccx not found (apt-get install calculix-ccx)" >&2; exit 1; }
python3 -c 'import gmsh' 2> /dev/null || { echo "hertz3d-vs-calculix: python3 has no gmsh (pip install gmsh)" >&2; exit 1; }
cargo build -q --release --example hertz3d_vs_calculix

python3 scripts/calculix-hertz3d.py --repeat "$repeat" --threads 2 > target/calculix-hertz3d.json.tmp
mv target/calculix-hertz3d.json.tmp target/calculix-hertz3d.json

RAYON_NUM_THREADS=2 target/release/examples/hertz3d_vs_calculix \
  --calculix target/calculix-hertz3d.json --repeat "$repeat" --out docs/hertz3d
