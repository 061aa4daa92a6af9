#!/usr/bin/env bash
# The 3D Hertz refinement table (issue #17 §4): makes the hexahedral,
# tetrahedral and non-matching hexahedral meshes of scenes/hertz3d.toml at element sizes h = 0.4 ... 0.05
# with scripts/make-hertz3d-mesh.py into target/hertz3d-refinement/, then
# solves the scene on each (examples/hertz3d_refinement.rs) and writes
# docs/hertz3d/hertz3d-refinement.{md,csv}.
#
#   scripts/hertz3d-refinement.sh [--max-equations N]
#   scripts/hertz3d-refinement.sh --kind tet --segmented    # a variant: its own files
#   scripts/hertz3d-refinement.sh --kind hexnm --dual        # non-matching hexahedra, dual
#   scripts/hertz3d-refinement.sh --kind hexnm073            # the block finer than the indenter
#   scripts/hertz3d-refinement.sh --kind hex --linear petsc --max-equations 2000000
#                                  # hexahedra to h = 0.05 with PETSc's default (the LDLᵀ
#                                  # of h = 0.05 does not fit); built with --features petsc
#
# Options go to examples/hertz3d_refinement.rs; without any, the table is
# also spliced into docs/benchmarks.md.
#
# Needs the `gmsh` Python package (pip install gmsh; the tetrahedral meshes
# depend on its version: 4.15.2 wrote the checked-in scenes/hertz3d-tet.msh,
# the same file as tet-0.1.msh here). A benchmark, never part of the test
# suite: the meshes are up to 14 MB each and not checked in.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=target/hertz3d-refinement
mkdir -p "$dir"
for h in 0.4 0.2 0.1 0.05; do
  [ -e "$dir/hex-$h.msh" ] || python3 scripts/make-hertz3d-mesh.py hex "$h" -o "$dir/hex-$h.msh"
done
for h in 0.4 0.2 0.1 0.07 0.05; do
  [ -e "$dir/hexnm-$h.msh" ] || python3 scripts/make-hertz3d-mesh.py hex-nonmatching "$h" -o "$dir/hexnm-$h.msh"
  [ -e "$dir/hexnm073-$h.msh" ] || python3 scripts/make-hertz3d-mesh.py hex-nonmatching "$h" --master-ratio 0.73 -o "$dir/hexnm073-$h.msh"
  [ -e "$dir/tet-$h.msh" ] || python3 scripts/make-hertz3d-mesh.py tet "$h" -o "$dir/tet-$h.msh"
done
cmp -s "$dir/hex-0.1.msh" scenes/hertz3d-hex.msh || echo "hertz3d-refinement: hex-0.1.msh differs from scenes/hertz3d-hex.msh" >&2
cmp -s "$dir/tet-0.1.msh" scenes/hertz3d-tet.msh || echo "hertz3d-refinement: tet-0.1.msh differs from scenes/hertz3d-tet.msh (another gmsh version?)" >&2
features=()
case " $* " in *" petsc "*) features=(--features petsc) ;; esac
cargo build -q --release "${features[@]}" --example hertz3d_refinement
RAYON_NUM_THREADS=2 target/release/examples/hertz3d_refinement "$dir" --out docs/hertz3d "$@"
if [ $# -eq 0 ]; then
  scripts/splice-docs.sh hertz3d-refinement docs/hertz3d/hertz3d-refinement.md docs/benchmarks.md
fi
