#include "render/image_point.h"

#include "cpu/trace.h"

namespace dicsynth {

ImagePoint projectToImage(const PreparedCamera& camera, dvec3 world_m) {
  ImagePoint p;
  const auto& m = camera.model;
  const dvec3 pc = camera.rotationCameraFromWorld * world_m + camera.translationCameraFromWorld;
  p.depth_m = pc.z;
  p.inFront = pc.z > 0;
  if (!p.inFront) return p;
  p.pixel_px = projectToPixel(m, world_m);
  if (m.distorted) {
    // The round trip through the inverse tells a fold-back: undistort() returns the root joined to
    // the image centre (prepare.cpp checks that it exists on the image's border and an 8 px grid).
    const dvec2 distorted{(p.pixel_px.x - m.cx) / m.fx, (p.pixel_px.y - m.cy) / m.fy};
    const dvec2 ideal = normalizedFromCamera(m, pc);
    p.folded = !(glm::length(undistort(m.brown, distorted) - ideal) <= 1e-9 * (1 + glm::length(ideal)));
  }
  const Camera& c = camera.camera;
  p.inImage = !p.folded && p.pixel_px.x >= -0.5 && p.pixel_px.x <= c.width_px - 0.5 && p.pixel_px.y >= -0.5 &&
              p.pixel_px.y <= c.height_px - 0.5;
  return p;
}

bool reachesFirst(const PreparedScene& scene, const PreparedCamera& camera, int object, dvec3 world_m,
                  double relativeTolerance) {
  // The chief ray: from the camera centre (Pinhole, ThinLens) or from the point's foot on the plane
  // Z = 0 (Orthographic). d = P − origin: the point itself is at t = 1.
  const dvec3 origin = chiefRayOrigin(camera.model, world_m);
  cpu::SurfaceHit hit;
  return cpu::traceNearest(scene, origin, world_m - origin, hit) && hit.object == object &&
         std::abs(hit.t - 1) <= relativeTolerance;
}

}  // namespace dicsynth
