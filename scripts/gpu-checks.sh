#!/bin/bash
# Runs on a machine with a real GPU, from the repository's root, with a bundle made by
# scripts/gpu-bundle.sh: the CPU-vs-GPU checks and the benchmarks whose figures bench/RESULTS.md
# records per device ("GPU machines"). Each step has a time limit and the whole a budget, so that a
# lease of a few minutes returns whatever finished; steps run in order of importance (correctness
# first) and one left out for lack of time says so in LOGDIR/summary.txt. Named STEPS run in the order
# named (e.g. the long `scenes` last, after the figures, on a short lease).
#   env       the driver, `dicsynth devices`, one small render per precision (pipeline compilation)
#   checks    dicsynth_gpu_checks but its longest case: the randomized NURBS test (1.08e6 rays per
#             precision), visibility, shading, analytic shapes, df64 arithmetic, under the
#             validation layer
#   scenes    its longest case: every scene of scenes/ in fp64, df64 and fp32 against the CPU
#   compare   `dicsynth compare scenes --downscale 4` in fp32, df64 and fp64
#   bench     `dicsynth bench` (run time versus error, Figure 1, NURBS plate, dogbone)
#   process   bench/bench_process.sh (whole processes, Figure 1, 1600x1200, 16 spp; fixed overhead)
#   sweep     bench/bench_sweep.sh (50 points of Figure 1 at 800x600, 4 spp) with the default layers
#             (one writer, then the default number) and with `--layers image`: issue 15's time per
#             point against the render-only time
#   phases    one render's phases (DICSYNTH_TIMINGS=1): Figure 1 fp32 with all layers (EXR zip, none,
#             rle; zip in bands of 64 to 1200 rows) and with the image alone, the dogbone in df64
#             and fp64 (on the H100 every frame took ~0.1 s whatever the precision: where the time
#             goes)
#   long      the randomized NURBS test's long run (140 scenes, 1.08e7 rays per precision)
#   cases     the test cases CASES names (doctest -tc patterns, comma-separated; e.g. those a step
#             cut off by its limit left), under the validation layer
# Left out of checks and cases: the cases that need lavapipe beside the GPU (they list and select
# it by name: the bundle carries none) and the one that reads a finite-element mesh (VTK's ~90 MB of
# libraries would not fit a lease's 64 MiB transfer beside the bundle).
# Seen on an NVIDIA H100 with 16 cores (2026-11-26, bench/RESULTS.md "GPU machines"): env 8 s, the
# NURBS test 53 s, scenes 189 s (NVIDIA compiles a pipeline per scene and precision, 1-5 s each,
# under validation), bench 22 s, process ~50 s. A machine lent for 15 minutes, start included,
# runs env to process in one call of ~420 s.
# Usage: scripts/gpu-checks.sh BUNDLE LOGDIR [BUDGET_S] [STEPS...]   (default 420 s, all steps)
set -u
B=$(cd "$1" && pwd)
LOG=$2
BUDGET=${3:-420}
shift $(($# < 3 ? $# : 3))
STEPS=${*:-env checks scenes compare bench process sweep phases long}
mkdir -p "$LOG"
LOG=$(cd "$LOG" && pwd)
ROOT=$(pwd)
T0=$(date +%s)

# The binaries carry the paths they were built with (the source folder: scenes, docs; the build
# folder: DS_BINARY of the CLI tests). Where those don't exist here, they are made to point here.
SRC=$(cat "$B/source-dir")
BUILD=$(cat "$B/build-dir")
if [ ! -e "$SRC" ]; then mkdir -p "$(dirname "$SRC")" && ln -s "$ROOT" "$SRC"; fi
mkdir -p "$BUILD"
for bin in dicsynth dicsynth_gpu_checks; do
  # Never replace another build's binary (on the machine that made the bundle, an older bundle).
  if [ -e "$BUILD/$bin" ] && ! cmp -s "$B/bin/$bin" "$BUILD/$bin"; then
    echo "gpu-checks: $BUILD/$bin differs from the bundle's: remake the bundle (scripts/gpu-bundle.sh)" >&2
    exit 2
  fi
  cp "$B/bin/$bin" "$BUILD/"
done

export LD_LIBRARY_PATH="$B/lib"
# Debian 12's libstdc++ only where the machine's is older (or missing).
"$BUILD/dicsynth" --version >/dev/null 2>&1 || export LD_LIBRARY_PATH="$B/lib:$B/lib-gcc"
export VK_LAYER_PATH="$B/layers"
# NVIDIA's container images keep the driver's manifest outside the loader's search path.
ICD=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -f "$ICD" ] && [ -z "${VK_DRIVER_FILES:-}" ]; then export VK_DRIVER_FILES=$ICD VK_ICD_FILENAMES=$ICD; fi
DS="$BUILD/dicsynth"
CHECKS="$BUILD/dicsynth_gpu_checks"

left() { echo $((BUDGET - ($(date +%s) - T0))); }
# step NAME LIMIT_S COMMAND: runs the shell command COMMAND (functions below exported) into
# LOGDIR/NAME.txt, unless fewer than 20 s of the budget are left.
step() {
  local name=$1 limit=$2 cmd=$3 l t rc
  l=$(left)
  if [ "$l" -lt 20 ]; then echo "$name: skipped, ${l} s of the budget left" >>"$LOG/summary.txt"; return; fi
  [ "$limit" -gt "$l" ] && limit=$l
  t=$(date +%s)
  timeout -k 5 "$limit" bash -c "$cmd" >>"$LOG/$name.txt" 2>&1
  rc=$?
  echo "$name: exit $rc after $(($(date +%s) - t)) s (limit $limit s)" >>"$LOG/summary.txt"
}

env_step() {
  nvidia-smi -L 2>&1 || true
  uname -a
  echo "LD_LIBRARY_PATH=$LD_LIBRARY_PATH VK_DRIVER_FILES=${VK_DRIVER_FILES:-}"
  ldd "$DS" | grep "not found" || true
  "$DS" --version
  "$DS" devices
  for p in fp32 df64 fp64; do
    local t=$(date +%s.%N)
    "$DS" render scenes/box.lua -o /tmp/gpu-checks-box --downscale 4 --precision $p
    echo "box $p: $(awk -v a="$t" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }') s (process, first run of the precision)"
  done
}
compare_step() {
  for p in fp32 df64 fp64; do "$DS" compare scenes --downscale 4 --precision $p; done
}
phases_step() {
  local args
  # The EXR compressions split the write phase: none (conversion and file I/O), rle, zip (the
  # default); and zip with wider bands per writePixels call (DICSYNTH_EXR_BAND_ROWS; 64 keeps at
  # most 4 threads compressing). On the H200 the write phase took 0.46 s with zip, as on 2 cores.
  for args in "figure1 fp32 all zip 64" "figure1 fp32 all none 64" "figure1 fp32 all rle 64" \
              "figure1 fp32 all zip 256" "figure1 fp32 all zip 512" "figure1 fp32 all zip 1200" \
              "figure1 fp32 image zip 64" "dogbone df64 all zip 64" "dogbone fp64 all zip 64"; do
    set -- $args
    echo "== $1 $2 --layers $3 --exr-compression $4, DICSYNTH_EXR_BAND_ROWS=$5"
    "$DS" render "scenes/$1.lua" -o /tmp/gpu-checks-phases --precision "$2" --layers "$3" --exr-compression "$4" >/dev/null
    DICSYNTH_EXR_BAND_ROWS=$5 DICSYNTH_TIMINGS=1 "$DS" render "scenes/$1.lua" -o /tmp/gpu-checks-phases \
      --precision "$2" --layers "$3" --exr-compression "$4" 2>&1 | grep '^timings'
  done
}
sweep_step() {
  # The default writes several points at once on many cores (job/output_writers.h); one writer for comparison.
  echo "== default layers, one writer"
  DICSYNTH_WRITERS=1 bench/bench_sweep.sh "$BUILD" 50 4 100
  echo "== default layers"
  bench/bench_sweep.sh "$BUILD" 50 4 100
  echo "== --layers image"
  EXTRA_OPTS="--layers image" bench/bench_sweep.sh "$BUILD" 50 4 100
  # A render's frames are written by the same rule: 20 frames of Figure 1 at 800x600, 4 spp,
  # one writer against the default, alternated.
  local round writers start
  for round in 1 2 3; do
    for writers in 1 default; do
      start=$(date +%s.%N)
      if [ "$writers" = 1 ]; then export DICSYNTH_WRITERS=1; else unset DICSYNTH_WRITERS; fi
      "$DS" render scenes/figure1.lua -o /tmp/gpu-checks-frames --downscale 2 --spp 4 --precision fp32 \
        --frames 0:19 >/dev/null
      unset DICSYNTH_WRITERS
      echo "render --frames 0:19, writers $writers: $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }') s"
    done
  done
}
long_step() { DICSYNTH_NURBS_RANDOM_SCENES=140 "$CHECKS" -tc="nurbs-random: GPU*"; }
export -f env_step compare_step sweep_step phases_step long_step
export DS CHECKS BUILD

SCENES_CASE='cpu-vs-gpu: every scene in scenes/*'
NOT_HERE='gpu: listDevices finds llvmpipe*,gpu: Context selects a device by index or name*,gpu: dicsynth devices lists*,cpu-vs-gpu: a fitted closed surface*'
CASES=${CASES:-}
export SCENES_CASE NOT_HERE CASES
for name in $STEPS; do
  case $name in
    env) step env 60 env_step ;;
    checks) step checks 150 'DICSYNTH_VALIDATION=1 "$CHECKS" --duration=true -tce="$SCENES_CASE,$NOT_HERE"' ;;
    cases) step cases 300 'DICSYNTH_VALIDATION=1 "$CHECKS" --duration=true -tc="$CASES" -tce="$NOT_HERE"' ;;
    scenes) step scenes 240 'DICSYNTH_VALIDATION=1 "$CHECKS" --duration=true -tc="$SCENES_CASE"' ;;
    compare) step compare 120 compare_step ;;
    bench) step bench 60 '"$DS" bench -o /tmp/gpu-checks-bench --runs 3' ;;
    process) step process 90 'bench/bench_process.sh "$BUILD" 3 16' ;;
    sweep) step sweep 130 sweep_step ;;
    phases) step phases 60 phases_step ;;
    long) step long 200 long_step ;;
    *) echo "gpu-checks: unknown step $name" >&2; exit 2 ;;
  esac
done
echo "total $(($(date +%s) - T0)) s" >>"$LOG/summary.txt"
cat "$LOG/summary.txt"
