// The sensor model: exposure, clipping, quantization. (Noise and post-processors come later and
// go between exposure and quantization.)
#include "sensor/sensor.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace dicsynth {
namespace {

// Round half up, exactly: floor(x + 0.5) is wrong for the largest double below 0.5 (the sum rounds
// to 1.0). The fraction x - floor(x) is exact for 0 <= x < 2^52, so comparing it with 0.5 is too.
double roundHalfUp(double x) {
  const double whole = std::floor(x);
  return x - whole >= 0.5 ? whole + 1.0 : whole;
}

}  // namespace

std::uint16_t digitize(double radiance, const Camera& camera) {
  DS_CHECK(camera.bitsPerPixel >= 1 && camera.bitsPerPixel <= 16,
           "camera " + camera.name + ": bitsPerPixel must be in 1..16");
  const double maxDigital = double((1u << camera.bitsPerPixel) - 1u);
  double signal = camera.exposure * radiance;  // full scale = 1
  if (std::isnan(signal)) signal = 0.0;        // documented: NaN reads black
  signal = std::clamp(signal, 0.0, 1.0);
  return static_cast<std::uint16_t>(roundHalfUp(signal * maxDigital));
}

std::vector<std::uint16_t> digitize(const std::vector<double>& radiance, const Camera& camera) {
  std::vector<std::uint16_t> digital(radiance.size());
  for (std::size_t i = 0; i < radiance.size(); ++i) digital[i] = digitize(radiance[i], camera);
  return digital;
}

}  // namespace dicsynth
