#!/bin/sh
# The fixed overhead of a `dicsynth render` process, old build against new (bench/RESULTS.md, "Speed
# as a user times it"): `render figure1.lua --precision fp32 --spp 1 --downscale 25` (64×48), wall
# time of whole processes, every cache warm (one untimed run of each build first: pipeline cache,
# prepared-texture cache, page cache), the two builds alternating, median of RUNS rounds, ratio
# new / old from the same rounds; then the phases of one more run of each (DICSYNTH_TIMINGS=1).
# Usage: bench/bench_startup.sh OLD_BUILD_DIR NEW_BUILD_DIR [RUNS]   (RUNS default 7)
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/common.sh"
OLD=$(binary_of "${1:-}")
NEW=$(binary_of "${2:-}")
RUNS=$(count RUNS "${3:-7}")
now() { date +%s.%N; }
run() { "$1" render "$SCENES/figure1.lua" -o "$OUT/o" --precision fp32 --spp 1 --downscale 25 >/dev/null 2>&1; }
timed() { t0=$(now); run "$1"; t1=$(now); awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f\n", b - a }'; }
check "$OLD" render "$SCENES/figure1.lua" -o "$OUT/o" --precision fp32 --spp 1 --downscale 25
check "$NEW" render "$SCENES/figure1.lua" -o "$OUT/o" --precision fp32 --spp 1 --downscale 25
: >"$OUT/old"
: >"$OUT/new"
for r in $(seq "$RUNS"); do
  timed "$OLD" >>"$OUT/old"
  timed "$NEW" >>"$OUT/new"
done
o=$(median <"$OUT/old")
n=$(median <"$OUT/new")
awk -v o="$o" -v n="$n" 'BEGIN { printf "fixed overhead (1 spp, 64x48, warm caches): old %.3f s, new %.3f s, new / old %.2f\n", o, n, n / o }'
for b in "$OLD" "$NEW"; do
  printf '%s:' "$b"
  DICSYNTH_TIMINGS=1 "$b" render "$SCENES/figure1.lua" -o "$OUT/o" --precision fp32 --spp 1 --downscale 25 2>&1 >/dev/null |
    sed -n 's/^timings: \([a-z]*\) \([0-9.]*\) s.*/ \1 \2/p' | tr -d '\n'
  echo
done
