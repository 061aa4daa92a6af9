#!/usr/bin/env bash
# Where the per-point batch spends its time: `perf record` of one criterion
# benchmark (default `points64/type6-batch$`, the 2D profile quoted in
# docs/kernels.md, "Kernel cost") in the release bench binary, then the
# symbols with the most samples.
# Needs Linux `perf`; a benchmark tool, not part of the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
filter="${1:-points64/type6-batch\$}"
cargo bench --bench kernels --no-run 2>&1 | tail -1
bin=$(ls -t target/release/deps/kernels-* | grep -v '\.d$' | head -1)
perf record -q -o target/perf-batch.data -- "$bin" --bench --profile-time 8 "$filter" > /dev/null
perf report -i target/perf-batch.data --no-children --stdio 2>/dev/null | grep -v '^#' | grep '%' | head -8
