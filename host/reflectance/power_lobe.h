#pragma once
// The parameters Shader.Phong and Shader.BlinnPhong share (phong.h, blinn_phong.h): the lobe's
// weight ks and its integer exponent n.
#include <cmath>

#include "core/math.h"

namespace dicsynth::reflectance {

// Shininess is an integer (1 ≤ n ≤ 10⁴): GLSL has no double pow, and x^n by repeated squaring
// costs ≤ 2 log2 n ≤ 28 products with a relative error ≤ 2n·2⁻⁵³ (≤ 2.2e-12 at n = 10⁴), far below
// the 1e-9 the fp64 GPU variant must meet; the CPU uses std::pow.
inline constexpr int kMaxShininess = 10000;

struct PowerLobe {
  double specular = 0.1;  // ks, the lobe's weight (ρ + ks ≤ 1 conserves energy at normal view)
  int shininess = 50;     // n

  template <class Params>
  static PowerLobe parse(const Params& p) {
    PowerLobe lobe;
    lobe.specular = p.number("specular", 0.1);
    p.require(lobe.specular >= 0, "specular", ">= 0", lobe.specular);
    const double n = p.number("shininess", 50);
    p.require(n == std::floor(n) && n >= 1 && n <= kMaxShininess, "shininess", "an integer in [1, 10000]", n);
    lobe.shininess = int(n);
    return lobe;
  }

  // GpuObject.material, read by GpuPhong and GpuBlinnPhong (shaders/reflectance/): ks, n, 0, 0.
  dvec4 gpu() const { return {specular, double(shininess), 0, 0}; }
};

}  // namespace dicsynth::reflectance
