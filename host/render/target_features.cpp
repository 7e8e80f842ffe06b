#include "render/target_features.h"

#include <cmath>

#include "render/image_point.h"

namespace dicsynth {

std::vector<TargetTruth> targetFeatureTruth(const PreparedScene& scene, std::size_t cameraIndex) {
  const PreparedCamera& camera = scene.cameras.at(cameraIndex);
  std::vector<TargetTruth> out;
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const PreparedObject& object = scene.objects[o];
    if (!object.target) continue;
    TargetTruth truth;
    truth.name = object.name;
    truth.object = o;
    truth.layout = object.target.get();
    const dmat4& wt = object.worldFromTarget;
    truth.R_cameraFromTarget = camera.rotationCameraFromWorld * dmat3(wt);
    truth.t_cameraFromTarget_m = camera.rotationCameraFromWorld * dvec3(wt[3]) + camera.translationCameraFromWorld;
    for (const TargetFeature& f : object.target->features) {
      FeatureTruth t;
      t.index = int(truth.features.size());
      t.row = f.row;
      t.col = f.col;
      t.target_m = f.target_m;
      const dvec4 world = object.worldFromTarget * dvec4(f.target_m, 1);  // rigid: w = 1
      t.world_m = dvec3(world) / world.w;
      const ImagePoint image = projectToImage(camera, t.world_m);
      t.depth_m = image.depth_m;
      t.inFront = image.inFront;
      if (t.inFront) {
        t.pixel_px = image.pixel_px;
        t.inImage = image.inImage;
        // Occlusion: the ray from the camera centre must first meet this very target, at the
        // feature (1e-9 is far above double rounding and far below any gap between two objects
        // that matters: 1 nm at 1 m).
        t.unoccluded = reachesFirst(scene, camera, int(o), t.world_m, 1e-9);
      }
      truth.features.push_back(t);
    }
    out.push_back(std::move(truth));
  }
  return out;
}

}  // namespace dicsynth
