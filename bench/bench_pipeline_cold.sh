#!/bin/sh
# What a scene's object count costs on a CPU device (lavapipe), old build against new
# (bench/RESULTS.md, "Unrolled object counts"): bench/grid_objects.lua with N objects (a floor and
# N - 1 spheres, 2 lights), per precision:
# - cold: the wall time of one `render --spp 1` whose shader caches are empty (a fresh
#   MESA_SHADER_CACHE_DIR and DICSYNTH_CACHE_DIR: the first render of that scene on a machine,
#   where lavapipe's JIT compiles the pipeline at its first dispatch), minus the same render warm:
#   the pipeline's compile, plus ~0.26 s of the texture's preparation (the prepare phase of
#   8 objects, fp32: 0.33 s cold, 0.07 s warm, 2026-11-29);
# - warm: the wall time of `render --spp 16 --layers image` (640 × 480), median of RUNS rounds, the
#   two builds alternating.
# Usage: bench/bench_pipeline_cold.sh OLD_BUILD_DIR NEW_BUILD_DIR [RUNS] [OBJECT_COUNTS] [PRECISIONS]
#        (RUNS default 3, OBJECT_COUNTS default "6 8", PRECISIONS default "fp32 df64 fp64")
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/common.sh"
OLD=$(binary_of "${1:-}")
NEW=$(binary_of "${2:-}")
RUNS=$(count RUNS "${3:-3}")
COUNTS=${4:-6 8}
PRECISIONS=${5:-fp32 df64 fp64}
for n in $COUNTS; do count OBJECT_COUNTS "$n" 2 >/dev/null; done
for p in $PRECISIONS; do case "$p" in fp32 | df64 | fp64) ;; *) usage "precision '$p': expected fp32, df64 or fp64" ;; esac; done
now() { date +%s.%N; }
# render BINARY OBJECTS PRECISION SPP [env...]: one render of the grid, its wall time in seconds.
render() {
  b=$1 n=$2 p=$3 spp=$4
  shift 4
  t0=$(now)
  env "$@" "$b" render "$HERE/grid_objects.lua" -o "$OUT/o" -D spheres=$((n - 1)) --precision "$p" --spp "$spp" \
    --layers image >"$OUT/run.log" 2>&1 || { cat "$OUT/run.log" >&2; echo "failed: $b, $n objects, $p" >&2; exit 1; }
  t1=$(now)
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f\n", b - a }'
}
cold() {  # BINARY OBJECTS PRECISION: cold minus warm wall time of a 1-spp render
  rm -rf "$OUT/cache"
  mkdir -p "$OUT/cache/mesa" "$OUT/cache/dicsynth"
  c=$(render "$1" "$2" "$3" 1 MESA_SHADER_CACHE_DIR="$OUT/cache/mesa" DICSYNTH_CACHE_DIR="$OUT/cache/dicsynth")
  w=$(render "$1" "$2" "$3" 1 MESA_SHADER_CACHE_DIR="$OUT/cache/mesa" DICSYNTH_CACHE_DIR="$OUT/cache/dicsynth")
  awk -v c="$c" -v w="$w" 'BEGIN { printf "%.1f", c - w }'
}
echo "objects precision | cold pipeline (s): old new | warm 16 spp render (s): old new new/old"
for n in $COUNTS; do
  for p in $PRECISIONS; do
    co=$(cold "$OLD" "$n" "$p")
    cn=$(cold "$NEW" "$n" "$p")
    render "$OLD" "$n" "$p" 1 >/dev/null  # the user's caches warm for the timed rounds
    render "$NEW" "$n" "$p" 1 >/dev/null
    : >"$OUT/old"
    : >"$OUT/new"
    for r in $(seq "$RUNS"); do
      render "$OLD" "$n" "$p" 16 >>"$OUT/old"
      render "$NEW" "$n" "$p" 16 >>"$OUT/new"
    done
    o=$(median <"$OUT/old")
    w=$(median <"$OUT/new")
    awk -v n="$n" -v p="$p" -v co="$co" -v cn="$cn" -v o="$o" -v w="$w" \
      'BEGIN { printf "%7d %-9s | %6.1f %6.1f | %6.3f %6.3f %5.2f\n", n, p, co, cn, o, w, w / o }'
  done
done
