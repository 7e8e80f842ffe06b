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

// The largest relative error of each operation, in a fixed order (the report's order).
std::vector<Df64OpError> evaluate(std::span<const Df64ProbeItem> items,
                                  std::span<const Df64ProbeResult> results);

// Items of DS_DF64_OP_FMA and the check of their results against std::fmaf (one rounding).
std::vector<Df64ProbeItem> makeFmaItems();
bool fmaResultsExact(std::span<const Df64ProbeItem> items, std::span<const Df64ProbeResult> results);

}  // namespace dicsynth::gpu::df64
