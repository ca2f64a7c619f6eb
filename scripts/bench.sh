#!/usr/bin/env bash
# Run the Rust benchmarks and the numpy baseline in the same run, and print the ratios.
# Needs python3 with numpy for the baseline (pip install numpy).
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(cargo bench --bench close 2>/dev/null)
echo "$out"
# Median column of divan's table, in seconds, for "<bench> <n>".
median() {
  echo "$out" | awk -v bench="$1" -v n="$2" '
    $0 ~ bench {inside=1; next}
    /^[├╰]─ [a-z]/ {inside=0}
    inside && $0 ~ "─ " n " " {
      line = $0; sub(/^│/, "", line); split(line, cols, "│"); m = cols[3]; gsub(/^ +| +$/, "", m); split(m, p, " ");
      unit = p[2]; v = p[1];
      if (unit == "ns") v /= 1e9; else if (unit == "µs") v /= 1e6; else if (unit == "ms") v /= 1e3;
      print v; exit }'
}
echo
printf "%-10s %6s %14s %14s %10s\n" "what" "N" "close median" "numpy median" "speed-up"
for n in 76 300 1000; do
  rust=$(median dgli_disk "$n")
  reps=$([ "$n" -ge 1000 ] && echo 3 || echo 7)
  py=$(python3 benches/numpy_baseline.py "$n" "$reps")
  awk -v n="$n" -v r="$rust" -v p="$py" 'BEGIN { printf "%-10s %6d %12.3f ms %12.3f ms %9.1fx\n", "disk", n, r*1e3, p*1e3, p/r }'
done
for n in 76 300 1000; do
  rust=$(median analyze_fold "$n")
  awk -v n="$n" -v r="$rust" 'BEGIN { printf "%-10s %6d %12.3f ms\n", "analyze", n, r*1e3 }'
done
# The fold-sequence search (a napkin in quarters seen flat and folded) against the one-fold
# analysis of the same cloth size, same run: issue 26 aims at 30x or less at N = 152.
for n in 152 300; do
  seq=$(median analyze_quarters "$n")
  one=$(median analyze_fold "$n")
  awk -v n="$n" -v s="$seq" -v o="$one" 'BEGIN { printf "%-10s %6d %12.3f ms %14s %9.1fx one fold\n", "sequence", n, s*1e3, "", s/o }'
done
