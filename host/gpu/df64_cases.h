#pragma once
// The df64 self-test's input set and its exact reference (internal to host/gpu/df64.cpp and the
// tests). Inputs are deterministic on every platform: a counter hash (shared/rng.h), not <random>.
#include <cstddef>
#include <span>
#include <vector>

#include "gpu/df64.h"
#include "shared/df64_probe.h"

namespace dicsynth::gpu::df64 {

// Probe items for every operation: the hard cases, then random items until each operation has at
// least `randomInputsPerOp` random results to check (components; one per dot product).
std::vector<Df64ProbeItem> makeItems(std::size_t randomInputsPerOp);

// The device's float division and sqrt, which df_div and df_sqrt build on: their largest
// relative errors in units of u = 2^-24 over the probe's float items (1 where none were probed:
// correct rounding, what the documented bounds assume), clamped to what Vulkan allows (division
// 2.5 ulp, sqrt as 1/inversesqrt). On an NVIDIA H100 df64 sqrt exceeded the bound derived for
// correctly rounded ones (bench/RESULTS.md), which suggests its float sqrt is not.
struct FloatAccuracy {
  double divU = 1;
  double sqrtU = 1;
};
FloatAccuracy floatAccuracy(std::span<const Df64ProbeItem> items, std::span<const Df64ProbeResult> results);

// The largest relative error of each operation, in a fixed order (the report's order). Each
// operation's bound is the documented one, div and sqrt evaluated with the measured FloatAccuracy.
std::vector<Df64OpError> evaluate(std::span<const Df64ProbeItem> items,
                                  std::span<const Df64ProbeResult> results);

// Items of DS_DF64_OP_FMA and the check of their results against std::fmaf (one rounding).
std::vector<Df64ProbeItem> makeFmaItems();
bool fmaResultsExact(std::span<const Df64ProbeItem> items, std::span<const Df64ProbeResult> results);

}  // namespace dicsynth::gpu::df64
