#include "render/target_features.h"

#include <cmath>

#include "cpu/trace.h"

namespace dicsynth {

std::vector<TargetTruth> targetFeatureTruth(const PreparedScene& scene, std::size_t cameraIndex) {
  const PreparedCamera& camera = scene.cameras.at(cameraIndex);
  const PinholeModel<double>& m = camera.model;
  const double w = camera.camera.width_px, h = camera.camera.height_px;
  std::vector<TargetTruth> out;
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const PreparedObject& object = scene.objects[o];
    if (!object.target) continue;
    TargetTruth truth;
    truth.name = object.name;
    truth.object = o;
    truth.layout = object.target.get();
    for (const TargetFeature& f : object.target->features) {
      FeatureTruth t;
      t.index = int(truth.features.size());
      t.row = f.row;
      t.col = f.col;
      t.target_m = f.target_m;
      const dvec4 world = object.worldFromTarget * dvec4(f.target_m, 1);  // rigid: w = 1
      t.world_m = dvec3(world) / world.w;
      const dvec3 pc = camera.rotationCameraFromWorld * t.world_m + camera.translationCameraFromWorld;
      t.depth_m = pc.z;
      t.inFront = pc.z > 0;
      if (t.inFront) {
        t.pixel_px = projectToPixel(m, t.world_m);
        // Far outside the image a Brown model can fold back inside: such a projection is not
        // where the feature is seen. The round trip through the inverse tells (prepare.cpp makes
        // sure the inverse is unique over the image itself).
        bool unique = true;
        if (m.distorted) {
          const dvec2 distorted{(t.pixel_px.x - m.cx) / m.fx, (t.pixel_px.y - m.cy) / m.fy};
          const dvec2 ideal{pc.x / pc.z, pc.y / pc.z};
          unique = glm::length(undistort(m.brown, distorted) - ideal) <= 1e-9 * (1 + glm::length(ideal));
        }
        t.inImage = unique && t.pixel_px.x >= -0.5 && t.pixel_px.x <= w - 0.5 && t.pixel_px.y >= -0.5 &&
                    t.pixel_px.y <= h - 0.5;
        // Occlusion: the ray from the camera centre towards the feature must first meet this very
        // target, at the feature (t = 1 along C + t (P − C); 1e-9 is far above double rounding and
        // far below any gap between two objects that matters: 1 nm at 1 m).
        cpu::SurfaceHit hit;
        t.unoccluded = cpu::traceNearest(scene, m.centre, t.world_m - m.centre, hit) && hit.object == int(o) &&
                       std::abs(hit.t - 1) <= 1e-9;
      }
      truth.features.push_back(t);
    }
    out.push_back(std::move(truth));
  }
  return out;
}

}  // namespace dicsynth
