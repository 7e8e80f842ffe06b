#pragma once
// The defective-pixel map of DefectivePixels { ... }: a DefectCode per pixel (sensor_model.h).
#include <cstdint>
#include <vector>

#include "model/sensor_model.h"

namespace dicsynth {

// Each pixel draws u in [0, 1) from the hash of (seed, camera, pixel) in dimension kDimSensorDefect
// with the frame fixed (kDefectFrame): dead if u < deadFraction, else hot if u < dead + hot, else
// stuck if u < dead + hot + stuck. So the map is the same in every frame, reproduced by the seed,
// and independent of threads. Then the explicit lists set their pixels (dead, then hot, then stuck:
// a pixel listed twice ends with the later kind). Explicit positions are in the scene's pixels and
// map to pixel (x / downscale, y / downscale) of the rendered image (integer division).
std::vector<std::uint8_t> defectMap(const DefectivePixels& defects, int width, int height, std::uint32_t seed,
                                    std::uint32_t cameraIndex, int downscale = 1);

}  // namespace dicsynth
