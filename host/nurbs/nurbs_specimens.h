#pragma once
// Builders of the common specimens as NURBS surfaces: the geometry behind Nurbs.plate,
// Nurbs.cylinderSegment and Nurbs.dogbone (their user documentation, parameter tables and checks
// are in nurbs_constructors.cpp, next to the code that reads the scene's parameters).
//
// Every builder is a function of its parameters only, and the knot vectors depend only on the
// parameters that are not deformations: a deformation (strain, necking, curvature) moves control
// points, and the same (u, v) stays the same material point. The specs must be valid (the scene
// reader checks them); the result passes validateNurbs.
#include <string>
#include <vector>

#include "core/math.h"
#include "nurbs/nurbs_surface.h"

namespace dicsynth::scene {

// A flat w × h plate in the xy-plane (facing -z), optionally bent about the y axis.
//   s = (u - 1/2) w (1 + strain.x)   arc length along the plate's x axis
//   y = (v - 1/2) h (1 + strain.y)
//   curvature k = 0: P = (s, y, 0), exactly (control points at the Greville abscissae)
//   k != 0:          P ≈ (sin(k s) / k, y, (1 - cos(k s)) / k), the profile interpolated at the
//                    Greville abscissae by a polynomial spline (errors measured and documented
//                    with Nurbs.plate): a bend without stretching, the edges move to +z if k > 0.
struct PlateSpec {
  dvec2 size_m{0, 0};
  double curvature_per_m = 0;
  dvec2 strain{0, 0};
  ivec2 spans{4, 4};
  ivec2 degree{3, 3};
};
NurbsSurface makePlate(const PlateSpec& spec);

// A segment of a circular cylinder of axis y through the origin: the arc of `angle` radians is
// centred on -z, P(phi, y) = (R sin phi, y, -R cos phi), phi from -angle/2 (u = 0) to angle/2;
// y from -h/2 (v = 0) to h/2. Exact: `arcs` equal rational quadratic arcs (each <= 90°) in u.
struct CylinderSegmentSpec {
  double radius_m = 0;
  double angle_rad = 0;  // (0, pi]
  double height_m = 0;
  int arcs = 1;          // >= angle / 90°
  int degreeV = 3;
};
NurbsSurface makeCylinderSegment(const CylinderSegmentSpec& spec);

// Exact NURBS forms of analytic shapes (Nurbs.from), in the shape's own frame.
// A flat parallelogram P(u, v) = origin + u·U + v·V, u, v in [0, 1]: one Bézier patch of the given
// degrees with evenly spaced control points, so the parametrization is exactly this linear one
// (Rectangle: origin (−w/2, −h/2, 0), U = (w, 0, 0), V = (0, h, 0): the rectangle's own (u, v)).
NurbsSurface makeParallelogram(const dvec3& origin, const dvec3& U, const dvec3& V, ivec2 degree);
// Face `face` ("-z", "+x", "+z", "-x", "-y", "+y": the 3 × 2 atlas cells of host/shapes/box.h's
// atlasUV, row by row) of a box of half edge lengths `halfSize`: the parallelogram whose (u, v) are
// the atlas cell's (s, t). Throws InputError for another face name.
NurbsSurface makeBoxFace(const dvec3& halfSize, const std::string& face, ivec2 degree);
// The sphere of radius r about the origin with the analytic sphere's poles (v = 0 at −y, 1 at +y)
// and seam (u = 0 and 1 at +z, u = 1/2 facing −z): four rational quadratic arcs around (u), two
// from pole to pole (v). Points are exactly on the sphere; (u, v) equal the analytic sphere's at
// the arcs' ends (every 90°) and differ in between (a rational arc is not uniform in angle).
NurbsSurface makeSphereNurbs(double radius_m);
// The side of a Shape.Cylinder (axis y, centred on the origin, open): a full turn of
// makeCylinderSegment in four arcs, degree 3 along y, the seam at the back (u = 0 and 1) closed
// exactly. (u, v) equal the analytic open cylinder's at the arcs' ends (every 90° in u) and in v
// everywhere (v = y/h + 1/2).
NurbsSurface makeCylinderSideNurbs(double radius_m, double height_m);

// A flat dogbone specimen in the xy-plane (facing -z), length along x, centred on the origin.
struct DogboneSpec {
  double length_m = 0, width_m = 0;            // whole specimen; grips are `width` wide
  double gaugeLength_m = 0, gaugeWidth_m = 0;  // the straight middle section
  double transitionLength_m = 0;               // along x, from gauge width to grip width
  double neckLength_m = 0;                     // extent of the neck bump, (0, gaugeLength]
  double necking = 0;       // relative width reduction at the centre
  double strain = 0;        // axial engineering strain
  double poissonRatio = 0;  // lateral contraction: width scaled by 1 - poissonRatio * strain
  ivec2 spans{1, 1};
};
NurbsSurface makeDogbone(const DogboneSpec& spec);
// Its knots along u (cubic, clamped): the profile's breakpoints, refined by spans.x. They depend
// on the geometry only, not on necking, strain or poissonRatio.
std::vector<double> dogboneKnotsU(const DogboneSpec& spec);

// The dogbone's outline in the reference (undeformed) configuration, and the neck's shape, both
// as functions of the material coordinate X (m, along the length, 0 at the centre):
//   halfWidth(X) = gw/2 + (w/2 - gw/2) S((|X| - gl/2) / transitionLength), S the C² cubic
//                  B-spline step (0 below 0, 1 above 1), and
//   neckBump(X) = the C² cubic B-spline bump of half-extent a = neckLength/2, 1 at X = 0:
//                 1 - 6 s² + 6 s³ (s = |X|/a ≤ 1/2), 2 (1 - s)³ (1/2 ≤ s ≤ 1), 0 beyond.
// The deformed edge is y = ±halfWidth(X) (1 - poissonRatio strain)(1 - necking neckBump(X)) at
// x = (1 + strain) X.
double dogboneHalfWidth(const DogboneSpec& spec, double x_m);
double dogboneNeckBump(const DogboneSpec& spec, double x_m);
double cubicBSplineStep(double t);  // S(t)

}  // namespace dicsynth::scene
