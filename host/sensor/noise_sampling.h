#pragma once
// Random variates of the sensor model, drawn from the counter-based hash of shaders/shared/rng.h:
// every number is a pure function of (seed, frame, camera, pixel, dimension, counter), so an image's
// noise does not depend on threads, tiling or the order pixels are processed in. No std::
// distributions (their algorithms differ between standard libraries).
#include <cstdint>

namespace dicsynth {

// The random dimensions of the sensor: 20..39, host-side only (shared/rng.h lists the GPU's, all below 20).
inline constexpr std::uint32_t kDimSensorShot = 20;     // Poisson shot noise
inline constexpr std::uint32_t kDimSensorRead = 21;     // Gaussian read noise
inline constexpr std::uint32_t kDimSensorDefect = 22;   // defective-pixel draw
inline constexpr std::uint32_t kDimSensorFixedPattern = 23;  // PRNU and DSNU (with kDefectFrame)
// The frame number used for the defect map and the fixed pattern (PRNU, DSNU): they belong to the
// sensor, not to one exposure, so they are the same in every frame.
inline constexpr std::uint32_t kDefectFrame = 0xffffffffu;

// A stream of uniform numbers for one pixel and dimension: the k-th number uses hash counters 2k
// and 2k+1 (as the `sample` argument of ds_sample_bits).
class PixelRandom {
 public:
  PixelRandom(std::uint32_t seed, std::uint32_t frame, std::uint32_t camera, std::uint32_t px,
              std::uint32_t py, std::uint32_t dim);
  // Uniform in [0, 1) with 53 random bits (27 + 26 from two hashes): every double k·2^-53.
  double uniform();

 private:
  std::uint32_t prefix_;  // ds_pixel_bits(seed, frame, camera, px, py) (shared/rng.h)
  std::uint32_t dim_;
  std::uint32_t counter_ = 0;
};

// A Poisson variate of mean `mean` >= 0 (finite).
//   mean < 10: inversion by sequential search from one uniform (exact up to double rounding).
//   mean >= 10: PTRS, the transformed rejection with squeeze of Hörmann (1993), "The transformed
//   rejection method for generating Poisson random variables", Insurance: Mathematics and
//   Economics 12:39-45; exact, ~1.1 uniform pairs per variate for any mean.
std::uint64_t poisson(double mean, PixelRandom& random);

// A standard normal variate (Box–Muller, cosine branch, from two uniforms).
double standardNormal(PixelRandom& random);

// log(k!), |error| < 1e-13 relative (a table below 16, Stirling's series above). Exposed for tests.
double logFactorial(std::uint64_t k);

}  // namespace dicsynth
