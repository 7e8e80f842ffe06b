#include "geometry/target_poses.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "geometry/prepared_scene.h"

namespace dicsynth {

std::string poseViolation(const TargetLayout& layout, const dmat4& worldFromTarget, const Camera& camera,
                          double margin_px) {
  const PinholeModel<double> m = pinholeModel(camera);
  const dmat3 cameraFromWorld = glm::transpose(m.worldFromCamera);
  // The printed side faces −z of the target frame: the camera must lie on that side.
  const dvec3 normal = dvec3(worldFromTarget[2]);
  const dvec3 origin = dvec3(worldFromTarget[3]);
  // (The chief ray that sees the target's origin starts at chiefRayOrigin: the camera centre, or for a
  // telecentric camera the origin's foot on the plane Z = 0.)
  if (!(glm::dot(normal, chiefRayOrigin(m, origin) - origin) < 0)) return "camera '" + camera.name + "' sees the target's back";
  const double lo_x = margin_px - 0.5, hi_x = camera.width_px - 0.5 - margin_px;
  const double lo_y = margin_px - 0.5, hi_y = camera.height_px - 0.5 - margin_px;
  for (const TargetFeature& f : layout.features) {
    const dvec3 world = dvec3(worldFromTarget * dvec4(f.target_m, 1));
    const dvec3 pc = cameraFromWorld * (world - m.centre);
    if (!(pc.z > 0)) return "a feature is behind camera '" + camera.name + "'";
    const dvec2 ideal = normalizedFromCamera(m, pc);
    dvec2 xy = ideal;
    if (m.distorted) {
      // Far outside the image a Brown model can fold back into it; such a point is not seen
      // where the formula puts it. Inside the image the inverse is unique (prepare.cpp checks it).
      xy = distort(m.brown, ideal);
      const dvec2 back = undistort(m.brown, xy);
      if (!(glm::length(back - ideal) <= 1e-9 * (1 + glm::length(ideal))))
        return "a feature is outside the valid field of camera '" + camera.name + "'s distortion";
    }
    const double x = m.fx * xy.x + m.cx, y = m.fy * xy.y + m.cy;
    if (!(x >= lo_x && x <= hi_x && y >= lo_y && y <= hi_y))
      return "a feature is outside the image of camera '" + camera.name + "'";
  }
  return {};
}

namespace {

// Uniform in [0, 1) from the top 53 bits: std::uniform_real_distribution's algorithm is left to
// the library, ours is the same everywhere.
double uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1p-53; }
double uniform(std::mt19937_64& rng, double a, double b) { return a + (b - a) * uniform01(rng); }

std::string formatDegrees(double radians) {
  std::ostringstream s;
  s << radians * 180 / kPi;
  return s.str();
}

}  // namespace

std::vector<dmat4> generateTargetPoses(const TargetLayout& layout, const std::vector<Camera>& cameras,
                                       const TargetPoseOptions& o) {
  DS_CHECK(!cameras.empty() && o.count >= 1 && o.distance_m.x > 0 && o.distance_m.y >= o.distance_m.x,
           "generateTargetPoses: invalid options");
  // The cameras' common view: mean centre, mean viewing direction, mean image-right direction.
  dvec3 base{0}, forward{0}, right{0};
  double tanHalfX = INFINITY, tanHalfY = INFINITY;  // of the narrowest camera (ideal pinhole)
  // Telecentric cameras see a field of constant size: half its width and height (m), narrowest.
  double orthoHalfX = INFINITY, orthoHalfY = INFINITY;
  for (const Camera& c : cameras) {
    const PinholeModel<double> m = pinholeModel(c);
    base += m.centre / double(cameras.size());
    forward += m.worldFromCamera[2];
    right += m.worldFromCamera[0];
    double& halfX = c.kindInfo().telecentric ? orthoHalfX : tanHalfX;
    double& halfY = c.kindInfo().telecentric ? orthoHalfY : tanHalfY;
    halfX = std::min(halfX, 0.5 * c.width_px / m.fx);
    halfY = std::min(halfY, 0.5 * c.height_px / m.fy);
  }
  const bool anyOrtho = !std::isinf(orthoHalfX);
  forward = glm::normalize(forward);
  right = glm::normalize(right - glm::dot(right, forward) * forward);
  const dvec3 down = glm::cross(forward, right);  // z × x = y: image-down

  std::mt19937_64 rng(o.seed);
  std::vector<dmat4> poses;
  for (int k = 0; k < o.count; ++k) {
    bool found = false;
    for (int attempt = 0; attempt < o.triesPerPose && !found; ++attempt) {
      // Draw every number of an attempt, in a fixed order, whether or not it is used.
      const double distance = uniform(rng, o.distance_m.x, o.distance_m.y);
      // Anywhere in the narrowest view, so that the poses reach the image's corners, where
      // the distortion is strongest (the rejection below keeps the features inside).
      const double ux = uniform(rng, -1, 1), uy = uniform(rng, -1, 1);
      const double offsetX = anyOrtho ? ux * std::min(distance * tanHalfX, orthoHalfX) : ux * distance * tanHalfX;
      const double offsetY = anyOrtho ? uy * std::min(distance * tanHalfY, orthoHalfY) : uy * distance * tanHalfY;
      const double tilt = uniform(rng, 0, o.maxTilt_rad);
      const double tiltAzimuth = uniform(rng, 0, 2 * kPi);
      const double roll = uniform(rng, -o.maxRoll_rad, o.maxRoll_rad);

      // Upright target facing the cameras' mean centre: z along the line of sight (away from
      // the cameras), x as close to the cameras' image-right as that allows, y = z × x.
      const dvec3 centre_m = base + distance * forward + offsetX * right + offsetY * down;
      const dvec3 z0 = glm::normalize(centre_m - base);
      const dvec3 x0 = glm::normalize(right - glm::dot(right, z0) * z0);
      const dvec3 y0 = glm::cross(z0, x0);
      // Tilt about an axis in the target's plane, then roll about its normal.
      const dvec3 tiltAxis = std::cos(tiltAzimuth) * x0 + std::sin(tiltAzimuth) * y0;
      const dmat4 rotation = glm::rotate(dmat4(1.0), tilt, tiltAxis) * glm::rotate(dmat4(1.0), roll, z0) *
                             dmat4(dvec4(x0, 0), dvec4(y0, 0), dvec4(z0, 0), dvec4(0, 0, 0, 1));
      // The rectangle's centre goes to centre_m: worldFromTarget · rectangleCentre_m = centre_m.
      dmat4 worldFromTarget = rotation;
      worldFromTarget[3] = dvec4(centre_m - dmat3(rotation) * layout.rectangleCentre_m, 1);

      found = std::all_of(cameras.begin(), cameras.end(), [&](const Camera& c) {
        return poseViolation(layout, worldFromTarget, c, o.margin_px).empty();
      });
      if (found) poses.push_back(worldFromTarget);
    }
    if (!found) {
      std::ostringstream msg;
      msg << "no pose found for target pose " << k + 1 << " after " << o.triesPerPose
          << " tries: none kept all " << layout.features.size() << " features of the target ("
          << layout.size_m.x << " x " << layout.size_m.y << " m) at least " << o.margin_px
          << " px inside every camera's image at distance {" << o.distance_m.x << ", " << o.distance_m.y
          << "} m with tilt up to " << formatDegrees(o.maxTilt_rad)
          << " degrees: the target is too large for the view there (increase 'distance', reduce "
             "'margin' or 'tilt', or make the cameras' views overlap)";
      throw InputError(msg.str());
    }
  }
  return poses;
}

}  // namespace dicsynth
