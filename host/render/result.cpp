#include "render/result.h"

#include <limits>

namespace dicsynth {

void CameraImage::resize(int width, int height) {
  width_px = width;
  height_px = height;
  const std::size_t n = pixelCount();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  radiance.assign(n, 0.0);
  depth_m.assign(n, nan);
  position_m.assign(n, dvec3(nan));
  normal.assign(n, dvec3(nan));
  uv.assign(n, dvec2(nan));
  objectId.assign(n, 0u);
}

}  // namespace dicsynth
