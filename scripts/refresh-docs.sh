#!/usr/bin/env bash
# Regenerates every measured table of the docs pages on this machine:
# the kernel benchmark and stability tables (docs/kernels.md), the solver
# scaling tables (docs/solver.md), the Hertz refinement study (docs/hertz),
# the contact patch test and the safety map (docs/benchmarks.md) and the
# study section (docs/study.md, with its CSV and plots in docs/study).
# Takes about twenty minutes (the scaling table's 10^6 equations alone
# several).
set -euo pipefail
cd "$(dirname "$0")/.."

# splice NAME FILE PAGE: replaces the lines between <!-- NAME:begin --> and
# <!-- NAME:end --> of PAGE (the docs page holding that marker) with the
# contents of FILE.
splice() {
  scripts/splice-docs.sh "$1" "$2" "$3"
}

cargo bench --bench kernels
cargo run -q --release --example bench_table > target/bench-table.md
splice bench target/bench-table.md docs/kernels.md
cargo run -q --release --example bench_table -- --faces > target/bench-faces-table.md
splice bench-faces target/bench-faces-table.md docs/kernels.md
cargo run -q --release --example bench_table -- --slip > target/bench-slip-table.md
splice bench-slip target/bench-slip-table.md docs/kernels.md

# one iteration from 1e3 to 1e6 equations with the LDL^T, against the LU up
# to 1e5 (several minutes; docs/scaling/scaling.md is the committed copy)
mkdir -p docs/scaling
cargo run -q --release --example scaling_table -- --linear ldlt,lu \
  --max-equations 1100000 --lu-max-equations 110000 > target/scaling-table.md
cp target/scaling-table.md docs/scaling/scaling.md
splice scaling docs/scaling/scaling.md docs/solver.md
# the same iteration in 3D (hexahedra, no contact), 1e4 to 1e5 equations,
# the fill to 1e6 from the pattern alone (about ten minutes, 11 GiB peak)
cargo run -q --release --example scaling_table -- --3d --linear ldlt \
  --fill-max-equations 1100000 > target/scaling3d-table.md
cp target/scaling3d-table.md docs/scaling/scaling3d.md
splice scaling3d docs/scaling/scaling3d.md docs/solver.md

cargo run -q --release --example hertz_refinement > target/hertz-table.md
splice hertz target/hertz-table.md docs/benchmarks.md

cargo run -q --release --example patch_table > target/patch-table.md
splice patch target/patch-table.md docs/benchmarks.md

# friction: Cattaneo-Mindlin (stick zone, shear, hysteresis loop) and the
# types under friction on the dragged block (docs/friction, PNG plots only)
cargo run -q --release --example mindlin > target/mindlin-table.md
splice mindlin target/mindlin-table.md docs/benchmarks.md
cargo run -q --release -- study scenes/dragged-block.toml --out docs/friction \
  --repeats 3 --steps 10,20,40 --no-heavy
rm -f docs/friction/*.svg

cargo run -q --release --example stability_sweep > target/stability-table.md
splice stability target/stability-table.md docs/kernels.md
splice stability-faces docs/stability/stability-faces.md docs/kernels.md

cargo run -q --release --example sliding_curves -- --steps 20 --out docs/sliding
cargo run -q --release --example adaptive_cost -- --out docs/adaptive
cargo run -q --release -- safety-map --out docs/safety-map
splice safety-map docs/safety-map/safety-map.md docs/benchmarks.md
# scripts/hertz-vs-calculix.sh needs CalculiX (calculix-ccx); when it is
# installed, refresh its table too.
if command -v ccx >/dev/null 2>&1; then
  scripts/hertz-vs-calculix.sh
  splice calculix docs/hertz/hertz-vs-calculix.md docs/benchmarks.md
fi

cargo run -q --release -- study --out docs/study --readme docs/study.md
