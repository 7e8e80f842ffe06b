#pragma once
// Options of one render, shared by both backends.
#include <cstdint>
#include <functional>
#include <string>

namespace dicsynth {

// GPU arithmetic (shaders/lib/real.glsl): fp32; df64 = float pairs (~45 bits) for the geometry,
// float for the rest; fp64 = native double (needs shaderFloat64).
enum class Precision { Fp32, Df64, Fp64 };
inline const char* toString(Precision p) {
  return p == Precision::Fp32 ? "fp32" : p == Precision::Df64 ? "df64" : "fp64";
}

struct RenderOptions {
  int samplesPerPixel = 4;  // stratified over the pixel's sensitive square (host/camera/sampling.h)
  std::uint32_t seed = 1;
  int frame = 0;
  Precision precision = Precision::Fp32;  // GPU only; the CPU reference is always double
  // false: the GPU backend hands back only radiance and objectId (--layers without P, N, uv, depth
  // or the layers derived from them: render/layers.h); the ground-truth vectors of CameraImage stay
  // empty. The CPU reference computes them anyway (they are its trace).
  bool geometry = true;
  // false: no sample ray is traced and CameraImage::radiance is 0 everywhere (--layers without
  // image, radiance, noise or defects: render/layers.h); only the pixel-centre ground-truth ray is.
  bool radiance = true;
  // Called from the rendering thread with the fraction of all cameras' pixels done, in [0, 1].
  std::function<void(double)> progress;
};

}  // namespace dicsynth
