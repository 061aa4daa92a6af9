#!/usr/bin/env bash
# Prints `gapsim kernel` output (stdout, or the error line and exit code) for
# both formulations, every type and a fixed set of configurations, including
# degenerate ones. Comparing the output of two builds shows whether the
# kernels' results changed:
#
#   scripts/kernel-outputs.sh target/release/gapsim > new.txt && diff old.txt new.txt
set -uo pipefail
bin=${1:?usage: kernel-outputs.sh PATH/TO/gapsim}
configs=(
  "0.3 0,1,2,1.1,2.1,0.9,-0.1,1.0"          # the worked example
  "-0.77 0,0,1,0,1.2,-0.01,-0.3,0.02"
  "1.0 1e6,1e6,1000001,1e6,1000001.3,999999.9,999999.8,1000000.2"
  "0.5 0,0,1e-6,2e-7,1.1e-6,1e-7,-1e-7,3e-7"
  "-1.0 0,0,3,4,5,1,-2,2"
  "0.1 0,0,1,0,0.5,1,0.5,-1"                # master perpendicular to slave
  "0.2 0,0,0,0,1,1,0,1"                     # zero-length slave segment
  "0.2 0,0,1,0,2,NaN,0,1"                   # NaN coordinate
)
for f in slave-normal closest-point; do
  for t in 1 2 3 4 5 6; do
    for c in "${configs[@]}"; do
      set -- $c
      echo "== $f type $t xi_s $1 nodes $2"
      "$bin" kernel --formulation "$f" --type "$t" --xi-s "$1" --nodes "$2" 2>&1
      echo "exit $?"
    done
  done
done
