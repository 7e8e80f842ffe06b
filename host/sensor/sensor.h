#pragma once
// The sensor: radiance before the sensor → digital numbers. Applied after either backend.
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace dicsynth {

// digital number = round(clamp(exposure * radiance, 0, 1) * (2^bitsPerPixel - 1)), rounding halves
// up. Radiance 1/exposure is full scale; brighter pixels saturate (clip) at 2^bits - 1.
// Rounding is exact (no floor(x + 0.5) double-rounding: 0.49999999999999994 rounds to 0).
// NaN radiance (a sample that failed numerically) reads 0, like an unlit pixel, rather than an
// undefined float → integer cast; +inf saturates. Throws Error if bitsPerPixel is outside 1..16.
std::uint16_t digitize(double radiance, const Camera& camera);
std::vector<std::uint16_t> digitize(const std::vector<double>& radiance, const Camera& camera);

}  // namespace dicsynth
