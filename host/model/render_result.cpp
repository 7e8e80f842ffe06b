#include "model/render_result.h"

#include <limits>

#include "core/parallel.h"

namespace dicsynth {

void CameraImage::resize(int width, int height, bool geometry) {
  width_px = width;
  height_px = height;
  const std::size_t n = pixelCount();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t g = geometry ? n : 0;
  // The six arrays filled side by side: ~84 bytes per pixel, first touched here (160 MB for
  // 1600 × 1200), one thread took 0.06–0.08 s, before every GPU render's first dispatch could
  // use them (bench/RESULTS.md, "Result images filled on all cores"). Small images in line.
  const auto fill = [&](std::size_t k) {
    switch (k) {
      case 0: position_m.assign(g, dvec3(nan)); break;
      case 1: normal.assign(g, dvec3(nan)); break;
      case 2: uv.assign(g, dvec2(nan)); break;
      case 3: depth_m.assign(g, nan); break;
      case 4: radiance.assign(n, 0.0); break;
      default: objectId.assign(n, 0u);
    }
  };
  if (n < (std::size_t(1) << 16)) {
    for (std::size_t k = 0; k < 6; ++k) fill(k);
  } else {
    parallelFor(6, fill);
  }
}

}  // namespace dicsynth
