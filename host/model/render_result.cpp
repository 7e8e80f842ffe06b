#include "model/render_result.h"

#include <limits>

namespace dicsynth {

void CameraImage::resize(int width, int height, bool geometry) {
  width_px = width;
  height_px = height;
  const std::size_t n = pixelCount();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  radiance.assign(n, 0.0);
  const std::size_t g = geometry ? n : 0;
  depth_m.assign(g, nan);
  position_m.assign(g, dvec3(nan));
  normal.assign(g, dvec3(nan));
  uv.assign(g, dvec2(nan));
  objectId.assign(n, 0u);
}

}  // namespace dicsynth
