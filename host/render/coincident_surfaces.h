#pragma once
// Coincident surfaces: two objects whose surfaces lie on each other over an area (a Shape.Rectangle
// laid on a box face or a plane as a decal, one shape twice). Along every ray there both are the
// nearest hit within the renderer's rounding, so which one a pixel sees flickers between them
// ("z-fighting"), pixel by pixel and differently in each precision, the CPU reference's included,
// and each may shadow the other (docs/precision.md, "Coincident surfaces"). Found before a run by
// tracing a coarse grid of chief rays per camera on the CPU reference and looking, along each ray,
// for a second object as near as the first; said as a warning, not refused (a decal in contact may
// be meant, and a lifted one is the fix).
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/prepared_scene.h"

namespace dicsynth {

// Chief rays traced per camera, spread over the image (coincident_surfaces.cpp).
inline constexpr int kCoincidenceRays = 1728;
// Two hits along a ray tie when their distances differ by at most this fraction of the nearer one:
// the gap precision.md asks a decal to be lifted by (fp32 and df64 place a hit to ~32 · 2⁻²⁴ ≈ 2e-6
// of the distance, over cos θ; 1e-5 leaves a factor 5, and a gap along the ray is already divided by
// cos θ).
inline constexpr double kCoincidenceGap = 1e-5;
// A pair is said when it ties along at least this many grid rays and this fraction of the grid rays
// that hit anything: objects in contact along a line (a box standing on a plate, a cylinder lying
// on one) tie only on the rays passing within ~1e-5 of the distance of that line, a few at most; a
// decal over 1 % of the image ties on ~17 of the 1728 rays.
inline constexpr std::size_t kCoincidenceMinRays = 8;
inline constexpr double kCoincidenceMinFraction = 0.01;

struct CoincidentPair {
  std::size_t first = 0, second = 0;  // indices into PreparedScene::objects, first < second
  std::size_t camera = 0;             // the camera whose grid found the most ties
  std::size_t rays = 0, raysHitting = 0;  // tied grid rays of that camera; its grid rays that hit anything
};

// The pairs tying over an area, in the order of their first object, then second.
std::vector<CoincidentPair> coincidentSurfaces(const PreparedScene& scene);

// "objects 'decal' and 'box' coincide: along 40 of the 1210 test rays of camera 'cam' that hit ..."
std::string describeCoincidence(const PreparedScene& scene, const CoincidentPair& pair);

// Warns of each pair coincidentSurfaces finds, once per pair and process (per call in Python:
// core/warning.h warnAtMost); render and compare call it (a compare that fails on a decal then says
// why).
void warnCoincidentSurfaces(const PreparedScene& scene);

}  // namespace dicsynth
