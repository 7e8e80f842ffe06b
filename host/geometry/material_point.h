#pragma once
// Material points: which point of an object's material a surface point is, and where that material
// point lies in another frame of the scene. The ground truth of motion (disp, flow) and of stereo
// correspondence (disparity) rests on this (render/ground_truth.h).
//
// A texture is glued on (u, v) (docs/design.md §3), so the material is identified by its (u, v): the
// material point seen in one frame is the point with the same object and the same (u, v) in any
// other frame, however the object moved or deformed (a NURBS whose control points move, a sphere
// whose radius grows, a rectangle whose size changes). One exception: a Plane repeats its texture
// tile, so its (u, v) are the same on every tile; its material coordinates are the unwrapped
// ones, u = x/w + 1/2, v = y/h + 1/2 of the plane's own frame (host/shapes/plane.h), without the fract.
//
// Everything here is double precision and evaluates the shape analytically (a NURBS by de Boor's
// algorithm on the scene's surface): a world point computed from material coordinates lies on the
// surface to rounding, whatever precision rendered the image the coordinates came from.
#include <optional>

#include "core/math.h"
#include "geometry/prepared_scene.h"

namespace dicsynth {

// The material coordinates of the surface point `world_m` of object `o` whose (u, v) are `uv`
// (as a renderer reports them). `world_m` is used only by a Plane (its tile).
dvec2 materialCoordinates(const PreparedObject& o, dvec2 uv, dvec3 world_m);

// The world position of the material point with coordinates `material` on object `o` (in the
// frame `o` was prepared for). Empty for a Triangle whose vertex uv are collinear (no inverse) and for a (u, v) of a
// Cylinder cap's atlas cell outside its disk (no material there).
// Coordinates slightly outside [0, 1]² (a renderer's rounding) extrapolate the analytic shapes and
// are clamped on a NURBS, whose evaluation stops at its knot domain.
std::optional<dvec3> worldPointOfMaterial(const PreparedObject& o, dvec2 material);

// worldPointOfMaterial(o, material).has_value(), without transforming the point (nor evaluating a
// NURBS surface, which always has one): what a reference frame derived for itself alone needs.
bool hasMaterialPoint(const PreparedObject& o, dvec2 material);

// A material point's world position and the side of its surface a viewer sees.
//
// A surface of zero thickness (a rectangle, an open tube, a NURBS sheet) is seen from either side,
// and both sides of one (u, v) are one material point here, where the specimen it stands for has two
// faces: a camera that sees the other side sees another material point. The side is told by the
// parametric normal n = ∂P/∂u × ∂P/∂v, whose orientation follows the material (a deformation that
// does not turn the surface inside out keeps it): a viewer at O sees side sign(n · (P − O)).
// Closed shapes (sphere, box, capped cylinder: their inside is never in view from outside) report
// no normal, as do points where n vanishes (a sphere's pole).
struct MaterialPointFrame {
  dvec3 point_m{0};
  std::optional<dvec3> normal;  // world frame, not normalized
};
std::optional<MaterialPointFrame> worldFrameOfMaterial(const PreparedObject& o, dvec2 material);

// +1 or −1: the side of the surface a viewer at `viewer_m` sees at `frame`; 0 where that cannot be
// told (no normal, or a ray within ~1e-9 rad of tangency).
int sideSeen(const MaterialPointFrame& frame, dvec3 viewer_m);

}  // namespace dicsynth
