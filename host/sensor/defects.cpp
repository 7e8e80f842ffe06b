// The defective-pixel map (defects.h).
#include "sensor/defects.h"

#include "core/error.h"
#include "core/parallel.h"
#include "sensor/noise_sampling.h"

namespace dicsynth {

std::vector<std::uint8_t> defectMap(const DefectivePixels& d, int width, int height, std::uint32_t seed,
                                    std::uint32_t cameraIndex, int downscale) {
  DS_CHECK(width > 0 && height > 0 && downscale >= 1, "defect map: image size");
  std::vector<std::uint8_t> map(std::size_t(width) * std::size_t(height), std::uint8_t(DefectCode::None));
  const double deadBelow = d.deadFraction, hotBelow = deadBelow + d.hotFraction,
               stuckBelow = hotBelow + d.stuckFraction;
  if (stuckBelow > 0) {
    parallelFor(std::size_t(height), [&](std::size_t y) {
      for (int x = 0; x < width; ++x) {
        PixelRandom random(seed, kDefectFrame, cameraIndex, std::uint32_t(x), std::uint32_t(y), kDimSensorDefect);
        const double u = random.uniform();
        DefectCode code = DefectCode::None;
        if (u < deadBelow) code = DefectCode::Dead;
        else if (u < hotBelow) code = DefectCode::Hot;
        else if (u < stuckBelow) code = DefectCode::Stuck;
        map[y * std::size_t(width) + std::size_t(x)] = std::uint8_t(code);
      }
    });
  }
  auto set = [&](const std::vector<PixelPosition>& list, DefectCode code) {
    for (const PixelPosition& p : list) {
      const int x = p.x_px / downscale, y = p.y_px / downscale;
      DS_CHECK(x >= 0 && x < width && y >= 0 && y < height, "defective pixel outside the image");
      map[std::size_t(y) * std::size_t(width) + std::size_t(x)] = std::uint8_t(code);
    }
  };
  set(d.dead, DefectCode::Dead);
  set(d.hot, DefectCode::Hot);
  set(d.stuck, DefectCode::Stuck);
  return map;
}

}  // namespace dicsynth
