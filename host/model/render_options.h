#pragma once
// Options of one render, shared by both backends.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace dicsynth {

// GPU arithmetic (shaders/lib/real.glsl): fp32; df64 = float pairs (~45 bits) for the geometry,
// float for the rest; fp64 = native double (needs shaderFloat64).
enum class Precision { Fp32, Df64, Fp64 };
// Every precision, cheapest first on a GPU: the one list that names, parsing (CLI, Python) and the
// calibration iterate over (the GPU variants themselves: CMakeLists.txt, gpu/renderer.cpp).
inline constexpr std::array<Precision, 3> kPrecisions{Precision::Fp32, Precision::Df64, Precision::Fp64};
inline const char* toString(Precision p) {
  return p == Precision::Fp32 ? "fp32" : p == Precision::Df64 ? "df64" : "fp64";
}
// The precision named `name` (toString's names); nullopt for any other text.
inline std::optional<Precision> parsePrecision(const std::string& name) {
  for (Precision p : kPrecisions)
    if (name == toString(p)) return p;
  return std::nullopt;
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
