#!/usr/bin/env bash
# A/B kernel benchmark in one criterion run: the kernels (codegen +
# contact-kernels) of an earlier revision against this tree's.
#
#   scripts/ab-kernel-bench.sh REV      # e.g. a commit before a refactoring
#
# Extracts REV into $AB_DIR/old (default /tmp/gapsim-ab; outside this
# workspace, so that REV's crates inherit from REV's own workspace), with
# its codegen and contact-kernels re-versioned to 0.0.0 so that both copies
# link into one binary, writes a scratch crate in $AB_DIR/crate depending on
# both, runs
# scripts/ab-kernels/bench.rs with criterion and prints the table of
# scripts/ab-kernels/table.rs. Takes a few minutes (two release builds of
# the kernels, ~40 benchmarks of 3 s).
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: ab-kernel-bench.sh REV}
root=$(pwd)
ab=${AB_DIR:-/tmp/gapsim-ab}
rm -rf "$ab/old"; mkdir -p "$ab/old" "$ab/crate"
git archive "$rev" | tar -x -C "$ab/old"
# Same package names, different versions: both can be linked.
for m in codegen contact-kernels; do
  sed -i 's/^version\.workspace = true$/version = "0.0.0"/' "$ab/old/$m/Cargo.toml"
  grep -q '^version = "0.0.0"$' "$ab/old/$m/Cargo.toml" || { echo "cannot re-version $rev's $m" >&2; exit 1; }
done

cat > "$ab/crate/Cargo.toml" <<TOML
[package]
name = "ab-kernels"
version = "0.0.0"
edition = "2024"
publish = false

[workspace]

[dev-dependencies]
old = { package = "contact-kernels", path = "$ab/old/contact-kernels" }
new = { package = "contact-kernels", path = "$root/contact-kernels" }
criterion = { version = "0.8", default-features = false, features = ["cargo_bench_support"] }
serde_json = "1"

[[bench]]
name = "ab"
path = "$root/scripts/ab-kernels/bench.rs"
harness = false

[[example]]
name = "table"
path = "$root/scripts/ab-kernels/table.rs"

[profile.bench]
lto = "thin"
debug = "line-tables-only"
TOML
mkdir -p "$ab/crate/src"; echo "" > "$ab/crate/src/lib.rs"
export CARGO_TARGET_DIR=$ab/target
(cd "$ab/crate" && cargo bench --bench ab ${AB_NO_RUN:+--no-run})
[ -z "${AB_NO_RUN:-}" ] || exit 0
(cd "$ab/crate" && CRITERION_DIR=$ab/target/criterion AB_REV=$rev cargo run -q --release --example table)
