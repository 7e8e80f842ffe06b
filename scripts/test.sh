#!/usr/bin/env bash
# Quick start, step 2 (and CI, through .ci/run): install what is missing, build, run the whole test
# suite on Vulkan (lavapipe when there is no GPU) with validation layers on.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
