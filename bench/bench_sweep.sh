#!/bin/sh
# Sweep benchmarks (bench/RESULTS.md, "Sweeps (issue 6)"), measured in one run:
#  1. time per point: one `dicsynth sweep` over POINTS points of Figure 1 at 800×600 (--downscale 2),
#     4 spp, vs one `dicsynth render` process per point (PROCS of them, same points);
#  2. per-point overhead: the steady-state time per point (the sweep's wall time minus that of a
#     sweep rendering its first point alone, i.e. without the one-off process, device and texture
#     start, over the other POINTS − 1 points) minus the GPU render time per point, as a fraction of
#     the steady-state time per point (the start-up is per sweep, not per point: shown apart);
#  3. peak memory (max RSS of the child process) of a 10-, MANY- and 8×MANY-point sweep of a 32×24
#     scene: no growth per point.
# Usage: bench/bench_sweep.sh [BUILD_DIR] [POINTS] [PROCS] [MANY]   (defaults: build 50 10 1000)
# EXTRA_OPTS="..." adds options to both the sweep and the render processes (e.g. --exr-compression rle);
# DICSYNTH_WRITERS=N sets how many points the sweep writes at once (default: 1 below 8
# hardware threads, else one per 4, at most 8). POINTS >= 2 (the steady state is measured over the
# points after the first); PROCS above POINTS is taken as POINTS.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/common.sh"
BIN=$(binary_of "${1:-build}")
POINTS=$(count POINTS "${2:-50}" 2)
PROCS=$(count PROCS "${3:-10}")
MANY=$(count MANY "${4:-1000}")
if [ "$PROCS" -gt "$POINTS" ]; then
  echo "PROCS $PROCS is more than POINTS $POINTS: $POINTS render processes" >&2
  PROCS=$POINTS
fi
OPTS="--downscale 2 --spp 4 --precision fp32 ${EXTRA_OPTS:-}"
now() { date +%s.%N; }

check "$BIN" render "$HERE/figure1_sweep.lua" -o "$OUT/warm" $OPTS  # options and scene work
# 1. One sweep process.
t0=$(now)
"$BIN" sweep "$HERE/figure1_sweep.lua" -o "$OUT/sweep" $OPTS --sweep angle=30:40:$POINTS >/dev/null
t1=$(now)
# GPU render time per point, from the manifest (render_seconds, second to last column; the device
# name is quoted and holds commas, so count from the end).
gpu=$(awk -F, 'NR > 1 { n = NF; s += $(n - 1) } END { printf "%.4f", s / (NR - 1) }' "$OUT/sweep/manifest.csv")

# The same sweep's first point alone (--shard 0/POINTS): process, device and texture start-up + 1 point.
t8=$(now)
"$BIN" sweep "$HERE/figure1_sweep.lua" -o "$OUT/first" $OPTS --sweep angle=30:40:$POINTS --shard 0/$POINTS >/dev/null
t9=$(now)

# One render process per point (the first PROCS points of the same sweep).
"$BIN" sweep "$HERE/figure1_sweep.lua" -o "$OUT/unused" --sweep angle=30:40:$POINTS --list | head -n "$PROCS" > "$OUT/points"
t2=$(now)
while read -r index folder value; do
  "$BIN" render "$HERE/figure1_sweep.lua" -o "$OUT/render/$folder" $OPTS -D "$value" >/dev/null
done < "$OUT/points"
t3=$(now)

# A rerun over the finished sweep: every point is checked (record, sizes, CRC-32) and skipped.
t4=$(now)
"$BIN" sweep "$HERE/figure1_sweep.lua" -o "$OUT/sweep" $OPTS --sweep angle=30:40:$POINTS >/dev/null  # all complete: skips
t5=$(now)

echo "sweep writers: ${DICSYNTH_WRITERS:-the default} on $(nproc) hardware threads"
awk -v ts="$t0" -v te="$t1" -v rs="$t2" -v re="$t3" -v ss="$t4" -v se="$t5" -v fs="$t8" -v fe="$t9" -v n="$POINTS" -v p="$PROCS" -v gpu="$gpu" 'BEGIN {
  sweep = (te - ts) / n; render = (re - rs) / p; rerun = se - ss; first = fe - fs
  steady = ((te - ts) - first) / (n - 1)
  printf "sweep: %d points in %.1f s: %.3f s per point (start-up included)\n", n, te - ts, sweep
  printf "render processes: %d in %.1f s: %.3f s per point\n", p, re - rs, render
  printf "speed-up per point (render process / sweep): %.2fx\n", render / sweep
  printf "first point alone (process, device, texture start + 1 point): %.2f s; steady state: %.3f s per point\n", first, steady
  printf "GPU render time per point in the sweep (manifest render_seconds): %.3f s\n", gpu
  printf "per-point overhead (steady-state time per point - GPU render) / steady-state time per point: %.1f %%\n", 100 * (steady - gpu) / steady
  printf "  (with the start-up spread over the %d points: %.1f %%)\n", n, 100 * (sweep - gpu) / sweep
  printf "rerun with every point complete (checks %d records and CRC-32s): %.2f s\n", n, rerun
}'

# 3. Peak memory: 10 vs MANY vs 8×MANY points of the 32×24 scene (GNU time's max RSS; a machine
# without /usr/bin/time, e.g. a lent GPU machine, skips this part with a message).
if [ ! -x /usr/bin/time ]; then
  echo "peak RSS: skipped, /usr/bin/time not installed (apt install time)"
  exit 0
fi
# rss POINTS FOLDER (a folder per run: the same count twice, e.g. MANY = 10, must not find the first
# run's complete points and skip them).
rss() { /usr/bin/time -f %M "$BIN" sweep "$HERE/tiny_sweep.lua" -o "$OUT/$2" --spp 1 --precision fp32 --sweep "shift=0:0.01:$1" 2>&1 >/dev/null | tail -n 1; }
r10=$(rss 10 rss_a)
t6=$(now)
r1000=$(rss "$MANY" rss_b)
t7=$(now)
r8000=$(rss "$((8 * MANY))" rss_c)
awk -v a="$r10" -v b="$r1000" -v c="$r8000" -v m="$MANY" -v t6="$t6" -v t7="$t7" 'BEGIN {
  t = t7 - t6
  printf "peak RSS: 10 points %.1f MiB, %d points %.1f MiB (ratio %.3f; the %d points took %.1f s), %d points %.1f MiB (ratio to %d: %.3f)\n",
    a / 1024, m, b / 1024, b / a, m, t, 8 * m, c / 1024, m, c / b }'
