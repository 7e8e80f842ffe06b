#pragma once
// The sensor: radiance before the sensor → digital numbers. Applied after either backend.
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace dicsynth {

// digital number = round(clamp(exposure * radiance, 0, 1) * (2^bitsPerPixel - 1)), rounding halves
// up. Radiance 1/exposure is full scale; brighter pixels saturate (clip) at 2^bits - 1.
std::uint16_t digitize(double radiance, const Camera& camera);
std::vector<std::uint16_t> digitize(const std::vector<double>& radiance, const Camera& camera);

}  // namespace dicsynth
