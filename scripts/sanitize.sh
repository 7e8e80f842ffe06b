#!/usr/bin/env bash
# A checking build: the test suite (or the ctest selection given as arguments, e.g. -LE gpu or
# -R nurbs) built and run under AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/. Any
# out-of-bounds access, use after free or undefined behaviour fails the case that hit it with a
# report (docs/development.md "Sanitizers"). Not part of scripts/test.sh: the instrumented build
# and its runs take much longer (figures there). Needs what scripts/test.sh needs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
BUILD=build-asan
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDICSYNTH_SANITIZE=address,undefined
cmake --build "$BUILD" -j"$(nproc)"
# Leaks are not checked: the Vulkan loader unloads the driver (lavapipe) before LeakSanitizer runs,
# which then reports the driver's allocations from an "<unknown module>" (128 bytes in every process
# that used the device, measured 2026-11-29) that no suppression can name; most areas run the
# dicsynth binary on the device for some cases.
export ASAN_OPTIONS="detect_leaks=0:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "$BUILD" --output-on-failure -j"$(nproc)" "$@"
