#pragma once
// The material-point round trip of one shape (tests/geometry/test_material_point.cpp runs it for
// every kind, test_cylinder.cpp for the cylinder): rays from a 64 × 48 camera at the origin traced
// on the CPU reference; each hit's material coordinates mapped back to a world point must be the hit.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <string>

#include "cpu/trace.h"
#include "geometry/material_point.h"
#include "scene/scene.h"
#include "temp_folder.h"

namespace dicsynth::test {

// `shape`: a Shape constructor, `transform`: an Object's transform, both as scene text. Returns the
// number of hits (of 2000 rays in a cone of ±0.12 rad) and checks the largest round-trip error.
inline int checkMaterialPointsOfHits(const TempFolder& dir, const std::string& shape, const std::string& transform) {
  const std::string path = dir.write(
      "scene.lua", "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                   "obj = Object.Simple { shape = " + shape + "; transform = " + transform + " }\n");
  const PreparedScene scene = prepareScene(loadScene(path, {}));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-0.12, 0.12);
  int hits = 0;
  double worst_m = 0;
  for (int k = 0; k < 2000; ++k) {
    const dvec3 d{angle(rng), angle(rng), 1};
    cpu::SurfaceHit hit;
    if (!cpu::traceNearest(scene, dvec3(0), d, hit)) continue;
    ++hits;
    const PreparedObject& o = scene.objects[std::size_t(hit.object)];
    const auto p = worldPointOfMaterial(o, materialCoordinates(o, hit.uv, hit.position));
    REQUIRE(p.has_value());
    worst_m = std::max(worst_m, glm::length(*p - hit.position));
  }
  // Double rounding of the hit and of the inverse mapping at 0.5 m: ~1e-16 relative times the
  // condition of atan2/acos near the sphere's poles or the cylinder's seam (~1e3) stays far below
  // 1e-12 m; the NURBS evaluation is exact to ~1e-15 m (tests/nurbs/test_nurbs.cpp).
  CHECK(worst_m < 1e-12);
  return hits;
}

}  // namespace dicsynth::test
