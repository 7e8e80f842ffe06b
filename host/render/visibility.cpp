#include "render/visibility.h"

#include "core/error.h"
#include "core/parallel.h"
#include "render/image_point.h"

namespace dicsynth {

std::vector<std::uint8_t> reachesFirstCpu(const PreparedScene& scene, std::size_t camera, std::span<const dvec3> points_m,
                                          std::span<const int> objects, double relativeTolerance) {
  DS_CHECK(points_m.size() == objects.size() && camera < scene.cameras.size(), "reachesFirstCpu: bad arguments");
  std::vector<std::uint8_t> reached(points_m.size(), 0);
  // Blocks of points in parallel: one point is one traced ray.
  constexpr std::size_t kBlock = 1024;
  parallelFor((points_m.size() + kBlock - 1) / kBlock, [&](std::size_t b) {
    const std::size_t end = std::min(points_m.size(), (b + 1) * kBlock);
    for (std::size_t i = b * kBlock; i < end; ++i)
      reached[i] = reachesFirst(scene, scene.cameras[camera], objects[i], points_m[i], relativeTolerance) ? 1 : 0;
  });
  return reached;
}

}  // namespace dicsynth
