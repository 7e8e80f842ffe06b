#!/bin/sh
# Visibility masks traced by the rendering device against the CPU reference (bench/RESULTS.md,
# "Visibility masks on the GPU"): whole `dicsynth render` processes of an old build (masks on the
# CPU) and a new one, alternating, one warm-up run each first (pipelines, driver shader cache);
# median wall seconds and median "truth" phase seconds (DICSYNTH_TIMINGS=1, summed over frames and
# cameras) over RUNS rounds, and the ratio new / old from the same rounds.
# Cases: the NURBS dogbone's frames 0 and 1 (flow.mask), the stereo plate (disparity.mask), 1 spp.
# Usage: bench/bench_visibility.sh OLD_BUILD_DIR NEW_BUILD_DIR [RUNS] (RUNS default 3;
# PRECISION=fp64 by default).
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/common.sh"
OLD=$(binary_of "${1:-}")
NEW=$(binary_of "${2:-}")
RUNS=$(count RUNS "${3:-3}")
P=${PRECISION:-fp64}
# "wall truth" seconds of one run.
run() {
  bin=$1
  shift
  start=$(date +%s.%N)
  DICSYNTH_TIMINGS=1 "$bin" render "$@" --spp 1 --precision "$P" -o "$OUT/o" >/dev/null 2>"$OUT/stderr"
  end=$(date +%s.%N)
  truth=$(awk '/^timings: truth/ { s += $3 } END { print s + 0 }' "$OUT/stderr")
  echo "$start $end $truth" | awk '{ printf "%.3f %.3f\n", $2 - $1, $3 }'
}
echo "| case ($P) | old wall s | new wall s | new / old | old truth s | new truth s |"
echo "|---|---|---|---|---|---|"
for case in dogbone stereo_plate; do
  if [ $case = dogbone ]; then args="$SCENES/dogbone.lua --frames 0:1"; else args="$SCENES/stereo_plate.lua"; fi
  # shellcheck disable=SC2086
  check "$OLD" render $args --spp 1 --precision "$P" -o "$OUT/o"
  # shellcheck disable=SC2086
  check "$NEW" render $args --spp 1 --precision "$P" -o "$OUT/o"
  : >"$OUT/old"
  : >"$OUT/new"
  for r in $(seq "$RUNS"); do
    # shellcheck disable=SC2086
    run "$OLD" $args >>"$OUT/old"
    # shellcheck disable=SC2086
    run "$NEW" $args >>"$OUT/new"
  done
  ow=$(cut -d' ' -f1 "$OUT/old" | median)
  nw=$(cut -d' ' -f1 "$OUT/new" | median)
  ot=$(cut -d' ' -f2 "$OUT/old" | median)
  nt=$(cut -d' ' -f2 "$OUT/new" | median)
  awk -v c=$case -v ow="$ow" -v nw="$nw" -v ot="$ot" -v nt="$nt" \
    'BEGIN { printf "| %s | %.2f | %.2f | %.2f | %.2f | %.2f |\n", c, ow, nw, nw / ow, ot, nt }'
done
