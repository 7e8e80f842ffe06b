#!/bin/sh
# The GPU's NURBS search, old build against new (bench/RESULTS.md, "GPU NURBS search with per-box
# certificates"): `dicsynth render SCENE --spp 4 --downscale 2 --precision P` for Figure 1 (no
# NURBS: must not move), the NURBS plate and the dogbone, every precision, the render phase as the
# process reports it (DICSYNTH_TIMINGS=1, "timings: render"), median of RUNS rounds in which the two
# builds alternate (one warm-up run each first: driver shader cache), ratio new / old from the same
# rounds, and Mrays/s (camera rays: pixels x (spp + 1), the +1 the ground-truth ray).
# Usage: bench/bench_nurbs_search.sh OLD_BUILD_DIR NEW_BUILD_DIR [RUNS]   (RUNS default 3)
# PRECISIONS="df64" and BENCH_SCENES="dogbone" restrict the table (default: all three of each).
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/common.sh"
OLD=$(binary_of "${1:-}")
NEW=$(binary_of "${2:-}")
RUNS=$(count RUNS "${3:-3}")
SPP=4
# Render seconds of one run, and its pixel count into $OUT/pixels.
render() {
  DICSYNTH_TIMINGS=1 "$1" render "$SCENES/$2.lua" -o "$OUT/o" --spp $SPP --downscale 2 --precision "$3" \
    >"$OUT/stdout" 2>"$OUT/stderr"
  sed -n 's/.*: \([0-9]*\)x\([0-9]*\), .*/\1 \2/p' "$OUT/stdout" | awk '{ s += $1 * $2 } END { print s }' >"$OUT/pixels"
  sed -n 's/^timings: render \([0-9.]*\) s.*/\1/p' "$OUT/stderr"
}
echo "| scene | precision | old s | new s | new / old | new Mrays/s |"
echo "|---|---|---|---|---|---|"
for scene in ${BENCH_SCENES:-figure1 nurbs_plate dogbone}; do
  for p in ${PRECISIONS:-fp32 df64 fp64}; do
    check "$OLD" render "$SCENES/$scene.lua" -o "$OUT/o" --spp $SPP --downscale 2 --precision "$p"
    check "$NEW" render "$SCENES/$scene.lua" -o "$OUT/o" --spp $SPP --downscale 2 --precision "$p"
    : >"$OUT/old"
    : >"$OUT/new"
    for r in $(seq "$RUNS"); do
      render "$OLD" $scene $p >>"$OUT/old"
      render "$NEW" $scene $p >>"$OUT/new"
    done
    o=$(median <"$OUT/old")
    n=$(median <"$OUT/new")
    px=$(cat "$OUT/pixels")
    awk -v s=$scene -v p=$p -v o="$o" -v n="$n" -v px="$px" -v spp=$SPP \
      'BEGIN { printf "| %s | %s | %.3f | %.3f | %.2f | %.1f |\n", s, p, o, n, n / o, px * (spp + 1) / n / 1e6 }'
  done
done
