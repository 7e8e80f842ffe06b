#pragma once
// Options of one render, shared by both backends.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/interruption.h"

namespace dicsynth {

// GPU arithmetic (shaders/lib/real.glsl): fp32; df64 = float pairs (~45 bits) for the geometry,
// float for the rest; fp64 = native double (needs shaderFloat64).
// The one list of precision variants, cheapest first on a GPU: X(Enum, name) per variant. The enum,
// kPrecisions, the names and parsing below (CLI, Python, calibration), the GPU's layouts (gpu/pack.h:
// Enum##Layout over gpu_layout.h's namespace `name`), its SPIR-V and dispatch (gpu/renderer.cpp) all
// expand it; CMakeLists.txt compiles render.comp once per name in its DS_PRECISIONS (with DS_NAME
// defined), and gpu/renderer.cpp fails to compile when the two lists differ.
#define DS_PRECISIONS(X) X(Fp32, fp32) X(Df64, df64) X(Fp64, fp64)

#define DS_PRECISION_ENUMERATOR(E, name) E,
enum class Precision { DS_PRECISIONS(DS_PRECISION_ENUMERATOR) };
#undef DS_PRECISION_ENUMERATOR
#define DS_PRECISION_VALUE(E, name) Precision::E,
inline constexpr std::array kPrecisions{DS_PRECISIONS(DS_PRECISION_VALUE)};
#undef DS_PRECISION_VALUE

inline const char* toString(Precision p) {
  switch (p) {
#define DS_PRECISION_NAME(E, name) \
  case Precision::E: return #name;
    DS_PRECISIONS(DS_PRECISION_NAME)
#undef DS_PRECISION_NAME
  }
  return "?";
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
  // or the layers derived from them: model/layers.h); the ground-truth vectors of CameraImage stay
  // empty. The CPU reference computes them anyway (they are its trace).
  bool geometry = true;
  // false: no sample ray is traced and CameraImage::radiance is 0 everywhere (--layers without
  // image, radiance, noise or defects: model/layers.h); only the pixel-centre ground-truth ray is.
  bool radiance = true;
  // Called from the rendering thread with the fraction of all cameras' pixels done, in [0, 1].
  std::function<void(double)> progress;
  // Polled before every CPU row and GPU tile (core/interruption.h); null: the render runs to its end.
  const StopFlag* stop = nullptr;
};

}  // namespace dicsynth
