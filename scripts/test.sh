#!/usr/bin/env bash
# Quick start, step 2 (and CI, through .ci/run): install what is missing, build, run the whole test
# suite on Vulkan (lavapipe when there is no GPU) with validation layers on.
# Arguments go to ctest (-L nurbs, -R name). Without arguments, and when the suite ran on
# dicsynth's own lavapipe (scripts/install-lavapipe.sh), the cases that use the Vulkan device
# (label gpu) run a second time on the system's lavapipe: the suite must pass on both
# (docs/performance.md "Which lavapipe").
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
# The driver of the device a render would use (`dicsynth devices` marks it with '*'); its df64
# self-test and calibration are cached with the tests' (tests/test_main.cpp).
chosen_driver() {
  DICSYNTH_CACHE_DIR="${DICSYNTH_CACHE_DIR:-$PWD/build/test-cache}" build/dicsynth devices | awk '/^\* / { mark = 1; next } mark && /driver:/ { sub(/^ *driver: */, ""); print; mark = 0 }'
}
if [ $# -eq 0 ] && [ -f .deps/lavapipe/dicsynth_lvp_icd.json ] && [ -z "${DICSYNTH_LAVAPIPE:-}" ] &&
   [ -z "${VK_ICD_FILENAMES:-}${VK_DRIVER_FILES:-}${VK_ADD_DRIVER_FILES:-}" ]; then
  own=$(chosen_driver)
  system=$(DICSYNTH_LAVAPIPE=system chosen_driver)
  if [ "$own" != "$system" ] && [[ "$system" == llvmpipe* ]]; then
    echo "dicsynth: the Vulkan cases (label gpu) again, on the system's lavapipe ($system)" >&2
    DICSYNTH_LAVAPIPE=system ctest --test-dir build --output-on-failure -j"$(nproc)" -L gpu
  fi
fi
