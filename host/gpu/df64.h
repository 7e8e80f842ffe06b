#pragma once
// df64 (double-float) support on the host: splitting doubles into the (hi, lo) float pairs that
// shaders/lib/df64.glsl computes with, and the on-device self-test that decides whether df64 may
// be used on a device (docs/design.md §4: a driver that fuses or reassociates float operations breaks
// the error-free transformations silently; only a measurement tells).
//
// The self-test runs tests/shaders/df64_probe.comp over a fixed, deterministic input set (random
// exponents and mantissas from the counter hash of shared/rng.h, plus hard cases: cancellation,
// the ends of df64's range, rounding ties, powers of two, ±0), compares every result with a
// long double reference and reports each operation's largest relative error. An operation passes
// at ≤ 2^-44. The result is cached per device (pipelineCacheUUID + driver version) in the folder
// of the pipeline cache, so only the first use of df64 on a device pays for it (pipeline
// compilation dominates: see bench/RESULTS.md or `dicsynth devices`).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dicsynth::gpu {

class Context;

// ---- Host split/join ----
struct Df64 {
  float hi = 0.0f;
  float lo = 0.0f;
};
// hi = float(x), lo = float(x − hi) (x − hi is exact in double). |x − (hi + lo)| ≤ 2^-49 |x| for
// 2^-100 ≤ |x| ≤ FLT_MAX (below, lo loses bits to float's subnormal range); exact when x is a
// float. From |x| >= 2^128·(1 − 2^-25), where float rounding overflows, hi = ±inf and lo = 0.
Df64 splitDf64(double x);
// hi + lo in double: exact for splitDf64's output (both lie on x's 53-bit grid).
double joinDf64(Df64 d);

// ---- Self-test ----
inline constexpr double kDf64MaxRelError = 0x1p-44;  // an operation passes at or below this

// Whether renders may use the fma TwoProd variant (DS_SPEC_DF64_FMA) where the self-test found fma
// exact and the variant within its bounds. They may not: on an NVIDIA H100 (driver 580.159.04,
// 2026-11-26) fma was exact and the fma variant passed the probe, whose operands come from a
// buffer, yet inside the render shader it kept only float accuracy where an operand is a
// compile-time constant: the uv of boxes (÷ 3), spheres and cylinders (÷ 2π) came out 4e-8 off
// (box.lua: 8489 px over the df64 bound; figure1.lua 60,107 px) while Dekker's split passed the
// same comparisons on the same machine (bench/RESULTS.md, "GPU machines"). A probe cannot prove
// what a compiler does to constants in another shader, so the fma variant is measured and
// reported (`dicsynth devices`) but renders use Dekker's split on every device.
inline constexpr bool kRendersUseFma = false;

struct Df64OpError {
  std::string name;            // "add", "mul", "div", "dot", … (see df64_cases.cpp)
  double maxRelError = 0.0;    // largest over the inputs (dot, cross: relative to Σ|aᵢbᵢ|)
  double log2 = 0.0;           // log2(maxRelError); -inf when every result was exact
  double bound = 0.0;          // the algorithm's documented bound (shaders/lib/df64.glsl); div's and
                               // sqrt's with the device's measured float division and sqrt
  std::size_t inputs = 0;      // results checked (components)
  std::size_t unnormalized = 0;  // results with fl(hi + lo) != hi (must be 0)
  bool passed() const { return maxRelError <= kDf64MaxRelError && unnormalized == 0; }
};

struct Df64SelfTest {
  bool fmaExact = false;  // fma(a, b, c) rounded once on every probe input
  bool useFma = false;    // DS_SPEC_DF64_FMA: kRendersUseFma and fmaPassed()
  bool passed = false;    // every operation of the variant in use passed
  std::vector<Df64OpError> dekker;  // TwoProd by Dekker's split (always measured)
  std::vector<Df64OpError> fma;     // TwoProd by fma (measured only where fmaExact)
  double seconds = 0.0;   // wall time of the measurement (that of the original run when cached)
  bool fromCache = false;
  std::string cachePath;  // "" when there is no cache folder

  // The variant in use (fma when useFma) and its worst operation (largest maxRelError; an
  // unnormalized result counts as failing first).
  const std::vector<Df64OpError>& ops() const { return useFma ? fma : dekker; }
  // fmaExact and every operation of the fma variant within its bounds (used in renders or not).
  bool fmaPassed() const;
  const Df64OpError& worst() const;
};

// The self-test for the context's device: read from the cache when a valid entry exists, else
// measured and written there (atomically; a damaged or foreign file is ignored and replaced).
// The renderer calls it once per device when df64 is requested; Context itself never runs it.
Df64SelfTest runDf64SelfTest(Context& context);

// runDf64SelfTest, then InputError unless it passed, naming the device, the worst operation, its
// error and the bound. Returns the self-test (useFma sets DS_SPEC_DF64_FMA).
Df64SelfTest requireDf64(Context& context);

// "pass (worst 2^-46.8, div)" / "FAIL (mul 2^-23.0 > 2^-44)"
std::string describeDf64(const Df64SelfTest& selfTest);

// ---- Lower level (tests) ----
struct Df64ProbeOptions {
  bool fma = false;  // DS_SPEC_DF64_FMA
  // Random inputs per operation, counted as results checked (components, vector widths 1..4
  // cycling; one per dot product), on top of the hard cases. The self-test uses kDf64SelfTestInputs.
  std::size_t randomInputsPerOp = 0;
};
inline constexpr std::size_t kDf64SelfTestInputs = 4096;

// Runs a probe (df64_probe_fp32 or a deliberately broken build of it) and measures every operation.
std::vector<Df64OpError> measureDf64(Context& context, std::span<const std::uint32_t> probeSpirv,
                                     const Df64ProbeOptions& options);
// Whether the device computes fma(a, b, c) with a single rounding on the probe's inputs.
bool probeFmaExact(Context& context, std::span<const std::uint32_t> probeSpirv);

}  // namespace dicsynth::gpu
