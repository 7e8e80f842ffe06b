#include "render/coincident_surfaces.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/warning.h"
#include "cpu/trace.h"

namespace dicsynth {

std::vector<CoincidentPair> coincidentSurfaces(const PreparedScene& scene) {
  std::map<std::pair<std::size_t, std::size_t>, CoincidentPair> pairs;
  if (scene.objects.size() < 2) return {};
  std::vector<double> t(scene.objects.size());
  std::vector<char> hit(scene.objects.size());
  std::vector<std::size_t> near;
  for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
    const PinholeModel<double>& model = scene.cameras[c].model;
    const Camera& cam = scene.cameras[c].camera;
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> ties;
    std::size_t raysHitting = 0;
    for (int k = 0; k < kCoincidenceRays; ++k) {
      // Roberts' R2 sequence over the image (pixel centres at integers, the image from −½ to
      // size − ½): spread evenly, and on no straight line, where a regular grid put a row of rays
      // exactly on the edge two triangles share (triangle.lua at ⅛ size: 16 "ties").
      constexpr double g = 1.32471795724474602596;  // the plastic number: g³ = g + 1
      const double fx = std::fmod(0.5 + k / g, 1.0), fy = std::fmod(0.5 + k / (g * g), 1.0);
      const CameraRay<double> ray = worldRay(model, dvec2(fx * cam.width_px - 0.5, fy * cam.height_px - 0.5));
      double nearest = kFarAway;
      for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        hit[o] = cpu::objectDistance(scene.objects[o], ray.origin, ray.direction, t[o]) ? 1 : 0;
        if (hit[o]) nearest = std::min(nearest, t[o]);
      }
      if (nearest == kFarAway) continue;
      ++raysHitting;
      // Every pair of objects both within the gap of the nearest hit (one shape three times
      // counts its three pairs): the few such objects first, so that a scene of many objects
      // costs one pass over them per ray.
      near.clear();
      for (std::size_t o = 0; o < scene.objects.size(); ++o)
        if (hit[o] && t[o] - nearest <= kCoincidenceGap * nearest) near.push_back(o);
      for (std::size_t a = 0; a < near.size(); ++a)
        for (std::size_t b = a + 1; b < near.size(); ++b) ++ties[{near[a], near[b]}];
    }
    for (const auto& [key, count] : ties) {
      if (count < kCoincidenceMinRays || double(count) < kCoincidenceMinFraction * double(raysHitting)) continue;
      CoincidentPair& p = pairs[key];
      if (count > p.rays) p = {key.first, key.second, c, count, raysHitting};
    }
  }
  std::vector<CoincidentPair> out;
  for (const auto& [key, p] : pairs) out.push_back(p);
  return out;
}

std::string describeCoincidence(const PreparedScene& scene, const CoincidentPair& p) {
  return "objects '" + scene.objects[p.first].name + "' and '" + scene.objects[p.second].name +
         "' coincide: along " + std::to_string(p.rays) + " of the " + std::to_string(p.raysHitting) +
         " test rays of camera '" + scene.cameras[p.camera].camera.name +
         "' that hit an object, both lie within 1e-5 of the distance of the nearest hit, where pixels flip "
         "between them and each may shadow the other, in every precision (z-fighting); lift one off the other "
         "by more than 1e-5 of the distance from the camera (docs/precision.md, coincident surfaces)";
}

void warnCoincidentSurfaces(const PreparedScene& scene) {
  for (const CoincidentPair& pair : coincidentSurfaces(scene))
    warnAtMost("coincident " + scene.objects[pair.first].name + " " + scene.objects[pair.second].name, 1,
               describeCoincidence(scene, pair));
}

}  // namespace dicsynth
