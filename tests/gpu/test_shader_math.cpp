// Shader library functions against C++: the RNG is bit-identical (the CPU reference and the GPU draw
// the very same sample positions), ds_atan2 is within a few ulps of std::atan2 in both precisions.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/math.h"
#include "gpu/buffer.h"
#include "gpu/compute.h"
#include "gpu_test_context.h"
#include "shared/rng.h"
#include "spirv/math_probe_df64.h"
#include "spirv/math_probe_fp32.h"
#include "spirv/math_probe_fp64.h"

using namespace dicsynth;

namespace {

// Real: the variant's real (inputs, ds_unit); Out: its hreal as stored (df64: a float pair).
template <class Real, class Out = Real>
struct ProbeResult {
  std::vector<uint> bits;
  std::vector<Real> unit;
  std::vector<Out> atan;
};

template <class Real, class Out = Real>
ProbeResult<Real, Out> runProbe(std::span<const std::uint32_t> spirv, const std::vector<uint>& rngIn,
                                const std::vector<Real>& atanIn) {
  auto& ctx = test::gpuContext();
  const std::uint32_t rngCount = std::uint32_t(rngIn.size() / 7), atanCount = std::uint32_t(atanIn.size() / 2);
  gpu::Buffer bRngIn(ctx, rngIn.size() * 4, gpu::BufferUse::Input);
  gpu::Buffer bRngOut(ctx, rngCount * 4, gpu::BufferUse::Readback);
  gpu::Buffer bAtanIn(ctx, atanIn.size() * sizeof(Real), gpu::BufferUse::Input);
  gpu::Buffer bAtanOut(ctx, atanCount * sizeof(Out), gpu::BufferUse::Readback);
  gpu::Buffer bUnitOut(ctx, rngCount * sizeof(Real), gpu::BufferUse::Readback);
  bRngIn.upload(rngIn.data(), rngIn.size() * 4);
  bAtanIn.upload(atanIn.data(), atanIn.size() * sizeof(Real));
  gpu::ComputePipeline pipeline(ctx, spirv, 5, 8);
  gpu::Buffer* buffers[] = {&bRngIn, &bRngOut, &bAtanIn, &bAtanOut, &bUnitOut};
  const std::uint32_t push[2] = {rngCount, atanCount};
  gpu::dispatchAndWait(ctx, pipeline, buffers, push, (std::max(rngCount, atanCount) + 63) / 64);
  ProbeResult<Real, Out> r;
  r.bits.resize(rngCount);
  r.unit.resize(rngCount);
  r.atan.resize(atanCount);
  bRngOut.download(r.bits.data(), rngCount * 4);
  bUnitOut.download(r.unit.data(), rngCount * sizeof(Real));
  bAtanOut.download(r.atan.data(), atanCount * sizeof(Out));
  return r;
}

std::vector<uint> rngInputs() {
  std::vector<uint> in;
  std::mt19937 gen(7);  // any inputs will do; this generator only picks them
  for (int i = 0; i < 20000; ++i) {
    const uint seed = gen(), frame = gen() % 100, cam = gen() % 4, x = gen() % 4096, y = gen() % 4096,
               s = gen() % 64, dim = gen() % 2;
    in.insert(in.end(), {seed, frame, cam, x, y, s, dim});
  }
  in.insert(in.end(), {0u, 0u, 0u, 0u, 0u, 0u, 0u});
  in.insert(in.end(), {0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu, 1u});
  return in;
}

template <class Real>
std::vector<Real> atanInputs() {
  std::vector<Real> in;
  // Every quadrant and octant boundary, tiny and huge ratios, then a dense sweep of angles.
  const Real special[][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1},
                             {Real(1e-30), 1}, {1, Real(1e-30)}, {Real(3), Real(-1e-20)}, {0, 0},
                             {0, Real(-0.0)}, {Real(-0.0), Real(-0.0)}, {Real(-0.0), 0}, {Real(-0.0), -1},
                             {Real(-0.0), 1}, {1, Real(-0.0)}, {-1, Real(-0.0)}};
  for (const auto& p : special) in.insert(in.end(), {p[0], p[1]});
  for (int i = 0; i < 40000; ++i) {
    const double a = -3.14159 + 6.28318 * (i + 0.5) / 40000, r = 0.001 + (i % 97) * 0.37;
    in.push_back(Real(r * std::sin(a)));
    in.push_back(Real(r * std::cos(a)));
  }
  return in;
}

template <class Real>
void checkAtan(const std::vector<Real>& in, const std::vector<Real>& out, double maxUlps) {
  double worst = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    // Blind to the sign of zero (atan2(−0, −1) = +π, atan2(+0, −0) = 0), as the CPU's shapes use it.
    const Real ref = atan2ZeroUnsigned(in[2 * i], in[2 * i + 1]);
    const double ulp = std::max(double(std::nextafter(std::abs(ref), Real(INFINITY)) - std::abs(ref)),
                                double(std::numeric_limits<Real>::denorm_min()));
    const double ulps = std::abs(double(out[i]) - double(ref)) / ulp;
    worst = std::max(worst, ulps);
  }
  MESSAGE("ds_atan2 worst error: " << worst << " ulp");
  CHECK(worst <= maxUlps);
}

}  // namespace

TEST_CASE("gpu: RNG is bit-identical in C++ and both shader variants") {
  const auto in = rngInputs();
  const auto r32 = runProbe<float>(spirv::math_probe_fp32, in, std::vector<float>{0, 1});
  const auto r64 = runProbe<double>(spirv::math_probe_fp64, in, std::vector<double>{0, 1});
  const auto rdf = runProbe<float, std::array<float, 2>>(spirv::math_probe_df64, in, std::vector<float>{0, 1});
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < r32.bits.size(); ++i) {
    const uint* a = &in[7 * i];
    const uint ref = ds_sample_bits(a[0], a[1], a[2], a[3], a[4], a[5], a[6]);
    mismatches += r32.bits[i] != ref || r64.bits[i] != ref || rdf.bits[i] != ref;
    mismatches += double(r32.unit[i]) != ds_unit(ref) || r64.unit[i] != ds_unit(ref) || double(rdf.unit[i]) != ds_unit(ref);
  }
  CHECK(mismatches == 0);
  test::expectNoValidationMessages();
}

TEST_CASE("rng: numbers are uniform and uncorrelated between neighbouring pixels") {
  // Mean 1/2 and variance 1/12 within 5 standard errors over n = 10^6 numbers; lag-1 correlation
  // between horizontally adjacent pixels below 5/√n.
  const int n = 1000000;
  double sum = 0, sum2 = 0, cross = 0;
  double prev = ds_unit(ds_sample_bits(1, 0, 0, 0, 0, 0, 0));
  for (int i = 0; i < n; ++i) {
    const double u = ds_unit(ds_sample_bits(1, 0, 0, uint(i % 1000 + 1), uint(i / 1000), 0, 0));
    sum += u;
    sum2 += u * u;
    cross += (u - 0.5) * (prev - 0.5);
    prev = u;
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  CHECK(std::abs(mean - 0.5) < 5 * std::sqrt(1.0 / 12 / n));
  CHECK(std::abs(var - 1.0 / 12) < 5 * std::sqrt(1.0 / 180 / n));  // var of u² terms: 1/180
  CHECK(std::abs(cross / n / (1.0 / 12)) < 5 / std::sqrt(double(n)));
}

TEST_CASE("gpu: ds_atan2 against std::atan2") {
  const auto in64 = atanInputs<double>();
  const auto r64 = runProbe<double>(spirv::math_probe_fp64, {0, 0, 0, 0, 0, 0, 0}, in64);
  // Two halvings (≈ 2 ulp each, relative) and the Horner sum: measured ≤ 4 ulp; bound 8.
  checkAtan(in64, r64.atan, 8);
  const auto in32 = atanInputs<float>();
  const auto r32 = runProbe<float>(spirv::math_probe_fp32, {0, 0, 0, 0, 0, 0, 0}, in32);
  checkAtan(in32, r32.atan, 8);
  test::expectNoValidationMessages();
}

TEST_CASE("gpu: ds_atan2 in df64 against long double") {
  // Float inputs, the df64 result (hi + lo) against atan2 in long double. About 40 df64 operations
  // (two halvings with sqrt and division, 12 Horner steps), each within 2^-44 relative
  // (self-tested), with no cancellation (the series' terms alternate but shrink by x² ≤ 0.04):
  // an accumulated bound of 2^-40 relative is generous; the measured worst is printed.
  const auto in = atanInputs<float>();
  const auto r = runProbe<float, std::array<float, 2>>(spirv::math_probe_df64, {0, 0, 0, 0, 0, 0, 0}, in);
  double worst = 0;
  int zerosWrong = 0;
  for (std::size_t i = 0; i < r.atan.size(); ++i) {
    const long double ref = atan2ZeroUnsigned((long double)in[2 * i], (long double)in[2 * i + 1]);
    const long double got = (long double)r.atan[i][0] + (long double)r.atan[i][1];
    if (ref == 0) {
      zerosWrong += got != 0;
      continue;
    }
    worst = std::max(worst, double(std::abs((got - ref) / ref)));
  }
  MESSAGE("df64 ds_atan2 worst relative error: 2^" << std::log2(worst));
  CHECK(worst <= 0x1p-40);
  CHECK(zerosWrong == 0);
  test::expectNoValidationMessages();
}
