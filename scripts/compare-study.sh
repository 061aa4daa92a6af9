#!/usr/bin/env bash
# Compares two study output directories (as written by `gapsim study --out DIR`)
# column by column, ignoring the timing columns (every `*_seconds` column):
# every other value must be identical, character for character (the CSV
# prints floats in their shortest round-trip form, so this is bit equality).
#
#   scripts/compare-study.sh OLD_DIR NEW_DIR
#
# Exits non-zero and prints the differing rows when they differ. Used to show
# that a restructuring changed no result: record a study before the change,
# rerun it after, compare.
set -euo pipefail
old=${1:?usage: compare-study.sh OLD_DIR NEW_DIR}
new=${2:?usage: compare-study.sh OLD_DIR NEW_DIR}

# Prints the CSV without its *_seconds columns.
strip_times() {
  awk -F, -v OFS=, '
    NR == 1 { for (i = 1; i <= NF; i++) keep[i] = ($i !~ /_seconds$/) }
    { line = ""; sep = ""
      for (i = 1; i <= NF; i++) if (keep[i]) { line = line sep $i; sep = OFS }
      print line }' "$1"
}

status=0
found=0
for a in "$old"/*.csv; do
  found=1
  b="$new/$(basename "$a")"
  if [ ! -f "$b" ]; then
    echo "missing in $new: $(basename "$a")"; status=1; continue
  fi
  if diff <(strip_times "$a") <(strip_times "$b") > /tmp/compare-study.$$; then
    echo "identical (timings aside): $(basename "$a") ($(($(wc -l < "$a") - 1)) rows)"
  else
    echo "DIFFERENT: $(basename "$a")"; cat /tmp/compare-study.$$; status=1
  fi
  rm -f /tmp/compare-study.$$
done
[ "$found" = 1 ] || { echo "no CSV files in $old"; exit 1; }
exit $status
