#!/bin/sh
# Whole-process speed as a user times it (bench/RESULTS.md, "Speed as a user times it"): wall time of
# complete `dicsynth render` processes from the shell, medians of RUNS interleaved rounds (each
# round runs every variant once, so drifts of a shared machine hit all alike), ratios in one run:
#   gpu       dicsynth render figure1.lua --precision fp32              (default layers: all)
#   gpu-img   the same with --layers image                              (the sensor image alone)
#   gpu-auto  dicsynth render figure1.lua (no --precision)              (the default precision,
#             auto: it may choose a slower precision than fp32 to meet --max-error-px)
#   cpu       dicsynth render figure1.lua --backend cpu                 (the double-precision reference)
#   cpu-img   the same with --layers image
#   povray    POV-Ray 3.7 on bench/figure1.pov, same size, samples and cores (skipped when `povray`
#             is not installed: apt install povray)
# plus the fixed overhead: `render --spp 1 --downscale 25` (64×48) run twice, the second timed.
# Usage: bench/bench_process.sh [BUILD_DIR] [RUNS] [SPP]   (defaults: build 3 16)
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/common.sh"
BIN=$(binary_of "${1:-build}")
RUNS=$(count RUNS "${2:-3}")
SPP=$(count SPP "${3:-16}")
CORES=$(nproc)
now() { date +%s.%N; }
# Wall seconds of one command (its output discarded).
timed() { t0=$(now); "$@" >/dev/null 2>&1; t1=$(now); awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f\n", b - a }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

POV=""
if command -v povray >/dev/null 2>&1; then
  POV=povray
  cp "$SCENES/speckle.tif" "$OUT/speckle.tif"
else
  echo "povray not installed: its column is skipped (apt install povray)" >&2
fi

GPU="$BIN render $SCENES/figure1.lua --precision fp32 --spp $SPP"
AUTO="$BIN render $SCENES/figure1.lua --spp $SPP"  # no --precision: auto
CPU="$BIN render $SCENES/figure1.lua --backend cpu --spp $SPP"
# Warm-up: driver shader cache, page cache of the texture, the precision calibration of `auto`
# (measured once per device and build, then cached) and its choice (not timed), read from the line
# on stdout ("..., gpu fp64 on ..."): stderr names it only when the calibration is measured.
check $GPU -o "$OUT/warm" --layers image
check $AUTO -o "$OUT/warm-auto" --layers image --downscale 25
chosen=$(sed -n 's/.*, gpu \([a-z0-9]*\) on .*/\1/p' "$OUT/check.log" | head -n 1)
check $CPU -o "$OUT/warm-cpu" --layers image --downscale 25
for r in $(seq "$RUNS"); do
  timed $GPU -o "$OUT/g" >> "$OUT/gpu"
  timed $GPU -o "$OUT/gi" --layers image >> "$OUT/gpu-img"
  timed $AUTO -o "$OUT/ga" >> "$OUT/gpu-auto"
  timed $CPU -o "$OUT/c" >> "$OUT/cpu"
  timed $CPU -o "$OUT/ci" --layers image >> "$OUT/cpu-img"
  if [ -n "$POV" ]; then
    # +A0.0 +AM1 +R4: every pixel supersampled on a 4×4 grid (16 samples, like --spp 16).
    (cd "$OUT" && timed povray +I"$HERE/figure1.pov" +O"$OUT/pov.png" +W1600 +H1200 +A0.0 +AM1 +R4 \
       +WT"$CORES" -D -GA) >> "$OUT/povray"
  fi
  $BIN render "$SCENES/figure1.lua" -o "$OUT/t" --precision fp32 --spp 1 --downscale 25 >/dev/null 2>&1
  timed $BIN render "$SCENES/figure1.lua" -o "$OUT/t" --precision fp32 --spp 1 --downscale 25 >> "$OUT/tiny"
done

g=$(median < "$OUT/gpu"); gi=$(median < "$OUT/gpu-img"); ga=$(median < "$OUT/gpu-auto")
c=$(median < "$OUT/cpu"); ci=$(median < "$OUT/cpu-img")
tiny=$(median < "$OUT/tiny")
echo "Figure 1, 1600x1200, $SPP spp, $CORES cores, median of $RUNS interleaved runs (s):"
echo "| variant | wall s | CPU reference / this |"
echo "|---|---|---|"
printf "| gpu fp32, all layers | %s | %s |\n" "$g" "$(ratio "$c" "$g")"
printf "| gpu fp32, --layers image | %s | %s (vs cpu --layers image: %s) |\n" "$gi" "$(ratio "$c" "$gi")" "$(ratio "$ci" "$gi")"
printf "| gpu, default precision (auto: %s), all layers | %s | %s |\n" "${chosen:-?}" "$ga" "$(ratio "$c" "$ga")"
printf "| cpu reference, all layers | %s | 1 |\n" "$c"
printf "| cpu reference, --layers image | %s | |\n" "$ci"
if [ -n "$POV" ]; then
  p=$(median < "$OUT/povray")
  printf "| POV-Ray 3.7 | %s | povray / gpu all: %s, povray / gpu image: %s |\n" "$p" "$(ratio "$p" "$g")" "$(ratio "$p" "$gi")"
fi
echo "fixed overhead (1 spp, 64x48, second run): $tiny s"
