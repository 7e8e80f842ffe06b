// Shape.Nurbs, the specimens built as NURBS surfaces: Nurbs.plate, Nurbs.cylinderSegment,
// Nurbs.dogbone, and Nurbs.from (analytic shapes' NURBS forms; Nurbs.deform: deform_constructors.cpp). Like every shape, a NURBS surface is defined in its own frame; `location` places
// that frame's origin (the control points are relative to it), and an Object's transform acts
// about the location (worldFromShape = translate(location) * transform).
//
// The specimen helpers are C++ constructors, not a Lua prelude: they read their parameters with the
// same Params reader as every constructor (unknown keys, types, finiteness, one-line messages), their
// errors and Shape::where name the user's line without any stack-level bookkeeping, and their
// numerics (spline interpolation, rational arcs) live in typed, tested code (nurbs_specimens.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <tuple>

#include "nurbs/nurbs_specimens.h"
#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "shapes/registry.h"

namespace dicsynth::scene {

namespace {

Shape nurbsShape(lua_State* L, const Params& p, NurbsSurface surface) {
  // The scene's NURBS data lives in C++, beyond the Lua memory limit: a loop keeping plates of a
  // million control points each reached 4.9 GB (the sandbox audit of 2026-11-28). Every surface a
  // constructor makes counts, kept or not.
  const std::uint64_t total = LuaSandbox::of(L).addNurbsControlPoints(surface.controlPoints.size());
  if (total > kMaxSceneNurbsControlPoints)
    p.fail("the scene's NURBS surfaces have " + std::to_string(total) + " control points in all (surfaces kept or not), " +
           "over the limit of " + std::to_string(kMaxSceneNurbsControlPoints) + " per scene");
  Shape shape;
  shape.where = LuaSandbox::of(L).here(L);
  shape.location_m = p.vec3("location").value_or(dvec3(0));
  shape.nurbs = std::make_shared<const NurbsSurface>(std::move(surface));
  return shape;
}

// Runs a validateNurbs check; its message becomes "<constructor>: <message>".
template <class Check>
void checked(const Params& p, Check check) {
  try {
    check();
  } catch (const InputError& e) {
    p.fail(e.what());
  }
}

// {a, b}: two integers in lo..hi (degree = {3, 3}, spans = {4, 4}), or `fallback` when absent.
ivec2 integerPair(const Params& p, const char* key, const char* shape, int lo, int hi,
                  ivec2 fallback) {
  const auto values = p.numbers(key, 2, 2, shape);
  if (!values) return fallback;
  for (double value : *values)
    if (value != std::floor(value) || value < lo || value > hi)
      p.fail(Params::quote(key) + " must be two integers in " + std::to_string(lo) + ".." +
             std::to_string(hi) + ", got " + formatNumber(value));
  return ivec2(static_cast<int>((*values)[0]), static_cast<int>((*values)[1]));
}

double positive(const Params& p, const char* key) {
  const double value = p.requiredNumber(key);
  p.require(value > 0, key, "> 0 (metres)", value);
  return value;
}

// Refuses a control net over the limit before anything of its size is built.
void checkCount(const Params& p, const char* what, long long countU, long long countV) {
  const long long points = countU * countV;
  if (points > static_cast<long long>(kMaxNurbsControlPoints))
    p.fail(std::string(what) + " give " + std::to_string(countU) + " × " + std::to_string(countV) +
           " = " + std::to_string(points) + " control points, more than the limit of " +
           std::to_string(kMaxNurbsControlPoints));
}

constexpr int kMaxSpans = static_cast<int>(kMaxNurbsControlPoints);

/* ------------------------------------------------------------------------------------------------
Shape.Nurbs: a NURBS surface (non-uniform rational B-spline; conventions of "The NURBS Book",
Piegl & Tiller) given by its control net. The control points are relative to `location`.

  Parameter     | Value               | Default   | Meaning
  --------------+---------------------+-----------+------------------------------------------------
  degree        | {p, q}              | required  | degrees along u and v, integers in 1..5
  knotsU        | {t1, t2, ...}       | required  | knots along u, non-decreasing, at least 2(p+1);
                |                     |           | countU = #knotsU - p - 1 control points along u
  knotsV        | {t1, t2, ...}       | required  | the same along v: countV = #knotsV - q - 1
  controlPoints | {{x, y, z}, ...}, m | required  | countU × countV points, row-major: entry
                |                     |           | i countV + j + 1 is P_ij (i along u, j along v)
  weights       | {w1, w2, ...}       | all 1     | one per control point, same order; in 1e-6..1e6,
                |                     |           | the largest at most 1000 × the smallest
  location      | {x, y, z}, m        | {0, 0, 0} | origin of the control points' frame

Rules (one-line errors name the entry: knotsU[5], controlPoints[7], weights[3], counted from 1):
a knot may repeat at most p + 1 times (q + 1 along v), and at most p times strictly inside the
domain [knotsU[p+1], knotsU[countU+1]] (so the surface stays in one piece); the domain must not be
empty; at most 1 048 576 control points (kMaxNurbsControlPoints), checked from the knot vectors
before the points are read.

(u, v) ∈ [0, 1]² is the knot domain, normalized. With clamped knots (first and last repeated p + 1
times) the corners of the surface are the corner control points and (u, v) = (0, 0) is P_00 =
controlPoints[1]: put it at the top-left as the default camera sees it (smallest x and y) and
P_i0 along +x for an upright, unmirrored texture, as on Shape.Rectangle.

Example: a flat 10 cm square, bilinear, 50 cm in front of the default camera
  Shape.Nurbs { degree = {1, 1}; knotsU = {0, 0, 1, 1}; knotsV = {0, 0, 1, 1};
                controlPoints = {{-0.05, -0.05, 0}, {-0.05, 0.05, 0},    -- i = 0: j = 0, 1
                                 { 0.05, -0.05, 0}, { 0.05, 0.05, 0}};   -- i = 1
                location = {0, 0, 0.5} }
------------------------------------------------------------------------------------------------ */
int shapeNurbs(lua_State* L) {
  Params p(L, "Shape.Nurbs",
           {"degree", "knotsU", "knotsV", "controlPoints", "weights", "location"});
  if (!p.has("degree")) p.fail("missing required 'degree' = {p, q}");
  const ivec2 degree = integerPair(p, "degree", "{p, q}", 1, kMaxNurbsDegree, ivec2(0));
  NurbsSurface s;
  s.degreeU = degree.x;
  s.degreeV = degree.y;
  for (auto [key, knots, d] : {std::tuple{"knotsU", &s.knotsU, degree.x},
                               std::tuple{"knotsV", &s.knotsV, degree.y}}) {
    auto values = p.numbers(key, 0, Params::kAnyCount, "{t1, t2, ...}");
    if (!values) p.fail(std::string("missing required '") + key + "' = {t1, t2, ...}");
    const std::size_t minimum = 2 * static_cast<std::size_t>(d + 1);
    if (values->size() < minimum)
      p.fail(Params::quote(key) + " must hold at least 2 × (degree + 1) = " +
             std::to_string(minimum) + " knots for degree " + std::to_string(d) + ", got " +
             std::to_string(values->size()));
    *knots = std::move(*values);
  }
  s.countU = static_cast<int>(s.knotsU.size()) - s.degreeU - 1;
  s.countV = static_cast<int>(s.knotsV.size()) - s.degreeV - 1;
  checked(p, [&] { validateNurbsKnots(s); });  // counts within the limit, knots valid

  const std::size_t count = static_cast<std::size_t>(s.countU) * s.countV;
  // The counts come from the knot vectors: a knot too many reads as a wrong number of points, so
  // the message shows where the counts come from (the NURBS trial of 2026-11-29).
  const std::string countText = "countU × countV = (#knotsU − degreeU − 1) × (#knotsV − degreeV − 1) = (" +
                                std::to_string(s.knotsU.size()) + " − " + std::to_string(s.degreeU + 1) + ") × (" +
                                std::to_string(s.knotsV.size()) + " − " + std::to_string(s.degreeV + 1) + ") = " +
                                std::to_string(s.countU) + " × " + std::to_string(s.countV) + " = " +
                                std::to_string(count);
  auto points = p.vec3List("controlPoints", count, countText);
  if (!points) p.fail("missing required 'controlPoints' = {{x, y, z}, ...} (" + countText + ")");
  s.controlPoints = std::move(*points);
  s.weights = p.numbers("weights", count, count, "{w1, w2, ...}, one per control point")
                  .value_or(std::vector<double>(count, 1.0));
  checked(p, [&] { validateNurbs(s); });
  pushUserdata(L, nurbsShape(L, p, std::move(s)));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Nurbs.plate: a rectangular plate as a NURBS surface, flat or bent into a circular cylinder, under
uniform strain. Like Shape.Rectangle it lies in the xy-plane of its frame, centred on `location`,
facing -z, with u along x and v along y: (u, v) = (0, 0) is the corner the default camera sees
top-left.

  Parameter | Value        | Default   | Meaning
  ----------+--------------+-----------+-----------------------------------------------------------
  size      | {w, h}, m    | required  | undeformed extent along x and y; > 0
  curvature | number, 1/m  | 0         | bends the plate about the y axis into a circular cylinder of
            |              |           | radius 1/|curvature|, without stretching it: the centre line
            |              |           | x = 0 stays at z = 0 and the edges move to +z (away from the
            |              |           | default camera: convex towards it) when > 0, to -z when < 0;
            |              |           | the bend angle |curvature| w (1 + ex) must be <= pi
  strain    | {ex, ey}     | {0, 0}    | uniform engineering strain: lengths along x and y (along the
            |              |           | arc when bent) scaled by 1 + ex and 1 + ey; each > -1
  spans     | {nu, nv}     | {4, 4}    | Bézier spans along u and v (uniform clamped knots, simple)
  degree    | {p, q}       | {3, 3}    | degrees along u and v, 1..5 (C^(p-1) across spans)
  location  | {x, y, z}, m | {0, 0, 0} | centre of the plate

Material points: (u, v) is the point X = (u - 1/2) w, Y = (v - 1/2) h of the undeformed flat
plate. With s = (1 + ex) X, y = (1 + ey) Y and k = curvature:
  k = 0:   P(u, v) = location + (s, y, 0)                          exactly (z = 0, x linear in u)
  k != 0:  P(u, v) = location + (sin(k s)/k, y, (1 - cos(k s))/k)  approximately (below)
so changing `strain` or `curvature` moves every material point as a uniform stretch or a pure bend
would, and the texture, glued on (u, v), moves with it. The knots depend on spans and degree only.

Approximation when bent: the profile (x(s), z(s)) is interpolated at the Greville abscissae by a
polynomial spline (weights 1); along y the surface is exact, and the corners (u, v ∈ {0, 1}) are
exactly on the cylinder. Polynomial rather than the exact rational circle because a rational arc
cannot follow arc length: within an arc of angle a its speed varies by a factor 1 + tan²(a/4), a
fake strain pattern in the texture (1e-3 for 7° arcs), while the spline keeps every error of
order a⁴. Measured for degree 3 (tests/nurbs/test_nurbs_specimens.cpp), with a = |k| w (1 + ex) / nu the bend
angle of one span:
  distance to the cylinder                                <= 3.5e-3 a⁴ / |k|
  arc length from the centre line - (u - 1/2) w (1 + ex)  <= 6e-4 a⁴ / |k|
  |dP/du| / (w (1 + ex)) - 1, a fake strain               <= 1e-2 a⁴
E.g. w = 0.1 m, k = 5 /m (radius 20 cm), 4 spans: a = 0.125, distance 1.5e-7 m, arc length 8e-9 m,
fake strain 2e-6; with 8 spans all 16 times smaller. Use more spans for stronger bends. Other
degrees, measured at a = 0.125 (w = 0.1 m, k = 10 /m, 8 spans); odd degrees do best:
  degree                1        2        3        4        5
  distance (m)          2.0e-4   2.2e-7   7.7e-8   1.9e-10  2.5e-11
  arc length (m)        3.1e-6   1.6e-6   3.4e-9   1.1e-9   2.8e-12
  fake strain           2.6e-3   1.3e-3   1.7e-6   4.1e-7   1.2e-9

Example: plate = Object.Simple { shape = Nurbs.plate { size = {0.1, 0.075}; strain = {0.01, -0.003};
                                                       location = {0, 0, 0.4} } }
------------------------------------------------------------------------------------------------ */
int nurbsPlate(lua_State* L) {
  Params p(L, "Nurbs.plate", {"size", "curvature", "strain", "spans", "degree", "location"});
  PlateSpec spec;
  const auto size = p.vec2("size", "{w, h}");
  if (!size) p.fail("missing required 'size' = {w, h} (metres)");
  for (double s : {size->x, size->y}) p.require(s > 0, "size", "> 0 (metres) in w and h", s);
  spec.size_m = *size;
  spec.curvature_per_m = p.number("curvature", 0.0);
  spec.strain = p.vec2("strain", "{ex, ey}").value_or(dvec2(0));
  for (double e : {spec.strain.x, spec.strain.y})
    p.require(e > -1, "strain", "> -1 in x and y", e);
  spec.spans = integerPair(p, "spans", "{nu, nv}", 1, kMaxSpans, ivec2(4, 4));
  spec.degree = integerPair(p, "degree", "{p, q}", 1, kMaxNurbsDegree, ivec2(3, 3));
  checkCount(p, "'spans' and 'degree'", spec.spans.x + spec.degree.x,
             spec.spans.y + spec.degree.y);
  const double angle = std::fabs(spec.curvature_per_m) * spec.size_m.x * (1 + spec.strain.x);
  if (!(angle <= kPi * (1 + 1e-12)))
    p.fail("the bend angle |curvature| × w × (1 + ex) must be <= pi (half a cylinder), got " +
           formatNumber(angle));
  NurbsSurface surface = makePlate(spec);
  checked(p, [&] { validateNurbs(surface); });
  pushUserdata(L, nurbsShape(L, p, std::move(surface)));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Nurbs.cylinderSegment: part of a circular cylinder of axis y, exact (rational), the middle of its
arc facing -z (the default camera).

  Parameter | Value        | Default   | Meaning
  ----------+--------------+-----------+-----------------------------------------------------------
  radius    | number, m    | required  | > 0
  angle     | number, rad  | required  | angle of the arc, in (0, pi] (at most half the cylinder)
  height    | number, m    | required  | extent along the axis (y); > 0
  arcs      | integer      | ceil(angle| number of equal rational arcs along u, >= ceil(angle /
            |              |  / 90°)   | 90°) and <= 64: more arcs, more uniform speed (below)
  degreeV   | integer      | 3         | degree along v (the straight direction), 1..5
  location  | {x, y, z}, m | {0, 0, 0} | the axis point at mid-height; the middle of the surface is
            |              |           | at location + (0, 0, -radius)

P(u, v) = location + (R sin phi, y, -R cos phi), y = (v - 1/2) height exactly, phi increasing with
u from -angle/2 (u = 0: the left edge as the default camera sees it) to +angle/2 (u = 1); v = 0 at
the top. An Object's transform acts about the location, so rotate_y turns it about its own axis.

Construction: along u, `arcs` equal arcs (by default 1 up to 90°, 2 beyond), each a rational
quadratic Bézier (ends on the circle with weight 1, middle control point where the end tangents
meet, at distance R / cos(d/2) from the axis, weight cos(d/2) for an arc of angle d): every point
is on the circle up to rounding (measured 1.4e-17 m for R = 5 cm). Along v: one Bézier span of
degree degreeV, control points evenly spaced (v linear in y). The angle is not proportional to u:
within an arc, tan((phi - phi_mid)/2) = tan(d/4) (2t - 1) with t the arc's own parameter, so the
speed |dP/du| is 1 + tan²(d/4) times faster in the arc's middle than at its ends (17 % for a 90°
arc, 7 % for 60°, 0.4 % for 15°): a texture glued on (u, v) is that much denser at the ends of each
arc. Use more arcs where that matters.
Continuity: C-infinity inside each arc and along v. Where two arcs meet the knot is double: the
surface is the same smooth cylinder there (G2 and more: one circle), the parametrization is C1
(the speed's slope changes sign).

Example: tube = Object.Simple { shape = Nurbs.cylinderSegment { radius = 0.05; angle = degrees(120);
                                  height = 0.1; location = {0, 0, 0.55} } }
------------------------------------------------------------------------------------------------ */
int nurbsCylinderSegment(lua_State* L) {
  Params p(L, "Nurbs.cylinderSegment",
           {"radius", "angle", "height", "arcs", "degreeV", "location"});
  CylinderSegmentSpec spec;
  spec.radius_m = positive(p, "radius");
  spec.angle_rad = p.requiredNumber("angle");
  p.requireAngle(spec.angle_rad > 0 && spec.angle_rad <= kPi * (1 + 1e-12), "angle",
            "in (0, pi] radians (at most half a cylinder)", spec.angle_rad);
  spec.height_m = positive(p, "height");
  // At least enough arcs for 90° each (the tolerance keeps degrees(90) one arc despite rounding).
  const int fewest = std::max(1, static_cast<int>(std::ceil(spec.angle_rad / (kPi / 2) - 1e-12)));
  const long long arcs = p.integer("arcs").value_or(fewest);
  if (arcs < fewest || arcs > 64)
    p.fail("'arcs' must be in " + std::to_string(fewest) + "..64 (arcs of at most 90°), got " +
           std::to_string(arcs));
  spec.arcs = static_cast<int>(arcs);
  const long long degreeV = p.integer("degreeV").value_or(3);
  p.require(degreeV >= 1 && degreeV <= kMaxNurbsDegree, "degreeV", "in 1..5",
            static_cast<double>(degreeV));
  spec.degreeV = static_cast<int>(degreeV);
  NurbsSurface surface = makeCylinderSegment(spec);
  checked(p, [&] { validateNurbs(surface); });
  pushUserdata(L, nurbsShape(L, p, std::move(surface)));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Nurbs.dogbone: a flat tensile specimen (z = 0, facing -z) with its length along x, centred on
`location`: grips, C² transitions, a straight gauge section, an optional neck and a uniform axial
strain. (u, v) = (0, 0) is the top-left end as the default camera sees it.

  Parameter        | Value        | Default     | Meaning
  -----------------+--------------+-------------+------------------------------------------------
  length           | number, m    | required    | overall length (x); > 0
  width            | number, m    | required    | width of the grips (y); > 0
  gaugeLength      | number, m    | required    | length of the straight gauge section; > 0
  gaugeWidth       | number, m    | required    | its width, in (0, width]
  transitionLength | number, m    | required    | length (x) of each transition from gauge to
                   |              |             | grip; > 0, gaugeLength + 2 transitionLength <
                   |              |             | length (the grips keep some length)
  necking          | number       | 0           | relative reduction of the width at the centre,
                   |              |             | in [0, 1): 0.002 narrows the centre by 0.2 %
  neckLength       | number, m    | gaugeLength | extent of the neck along x, (0, gaugeLength]
  strain           | number       | 0           | uniform axial engineering strain; > -1
  poissonRatio     | number       | 0           | widths scaled by 1 - poissonRatio strain (> 0);
                   |              |             | in [-1, 0.5]
  spans            | {nu, nv}     | {1, 1}      | refinement: along u no span longer than
                   |              |             | length / nu (the profile's breakpoints are
                   |              |             | always knots); nv uniform spans along v
  location         | {x, y, z}, m | {0, 0, 0}   | centre of the specimen

Outline of the undeformed specimen, X along the length from the centre (gl = gaugeLength,
gw = gaugeWidth, w = width, tl = transitionLength):
  halfWidth(X) = gw/2 + (w - gw)/2 S((|X| - gl/2) / tl), S(t) = 0 for t <= 0, 1 for t >= 1 and,
  with T = 3t, T³/6 (T <= 1), 1/6 + d/2 + d²/2 - d³/3 with d = T - 1 (1 <= T <= 2),
  1 - (3 - T)³/6 (T >= 2): the uniform cubic B-spline step, monotone, C² (curvature continuous),
  steepest slope 9 (w - gw) / (8 tl) at mid-transition. (A circular fillet would be only G1: its
  curvature jumps where it meets the straight edges.)
Neck: bump(X) = 1 - 6 s² + 6 s³ (s = |X| / a <= 1/2), 2 (1 - s)³ (1/2 <= s <= 1), 0 beyond, with
  a = neckLength / 2: the cubic B-spline bump, C², 1 at the centre, in the gauge section.
Material points: (u, v) is the point X = (u - 1/2) length, Y = (2v - 1) halfWidth(X) of the
undeformed specimen (v = 0 on the edge y < 0, the top of the default camera's image); deformed:
  x = (1 + strain) X,   y = Y (1 - poissonRatio strain) (1 - necking bump(X)),   z = 0
so for the same (u, v) a change of strain or necking moves the point as in a tensile test, and the
knots never change (they depend on the geometry only). The texture's v spans the local width: in
the gauge section a texel is gw/w as tall as in the grips.

Construction, exact: bicubic B-spline (weights 1) with simple knots (C²) at the profile's
breakpoints (X = 0, ±a/2, ±a, ±gl/2, ±(gl/2 + tl/3), ±(gl/2 + 2 tl/3), ±(gl/2 + tl)); the x control
coordinates at the Greville abscissae (x exactly linear in u), the half width interpolated there.
Since the deformed outline is itself a cubic spline on these knots, the edge of the surface IS the
outline above, up to rounding (measured: below 1e-17 m on a 2 cm wide specimen).

Example: specimen = Object.Simple { shape = Nurbs.dogbone { length = 0.1; width = 0.02;
           gaugeLength = 0.03; gaugeWidth = 0.01; transitionLength = 0.015;
           necking = necking or 0; location = {0, 0, 0.3} } }
------------------------------------------------------------------------------------------------ */
int nurbsDogbone(lua_State* L) {
  Params p(L, "Nurbs.dogbone",
           {"length", "width", "gaugeLength", "gaugeWidth", "transitionLength", "necking",
            "neckLength", "strain", "poissonRatio", "spans", "location"});
  DogboneSpec spec;
  spec.length_m = positive(p, "length");
  spec.width_m = positive(p, "width");
  spec.gaugeLength_m = positive(p, "gaugeLength");
  spec.gaugeWidth_m = positive(p, "gaugeWidth");
  spec.transitionLength_m = positive(p, "transitionLength");
  if (spec.gaugeWidth_m > spec.width_m)
    p.fail("'gaugeWidth' must be <= 'width' = " + formatNumber(spec.width_m) + ", got " +
           formatNumber(spec.gaugeWidth_m));
  const double ends = spec.gaugeLength_m + 2 * spec.transitionLength_m;
  if (!(ends < spec.length_m * (1 - 1e-6)))
    p.fail("'gaugeLength' + 2 × 'transitionLength' = " + formatNumber(ends) +
           " must be < 'length' = " + formatNumber(spec.length_m) + " (the grips need a length)");
  spec.neckLength_m = p.number("neckLength", spec.gaugeLength_m);
  if (!(spec.neckLength_m > 0 && spec.neckLength_m <= spec.gaugeLength_m))
    p.fail("'neckLength' must be in (0, gaugeLength = " + formatNumber(spec.gaugeLength_m) +
           "] (the neck lies in the gauge section), got " + formatNumber(spec.neckLength_m));
  spec.necking = p.number("necking", 0.0);
  p.require(spec.necking >= 0 && spec.necking < 1, "necking", "in [0, 1)", spec.necking);
  spec.strain = p.number("strain", 0.0);
  p.require(spec.strain > -1, "strain", "> -1", spec.strain);
  spec.poissonRatio = p.number("poissonRatio", 0.0);
  p.require(spec.poissonRatio >= -1 && spec.poissonRatio <= 0.5, "poissonRatio", "in [-1, 0.5]",
            spec.poissonRatio);
  if (!(spec.poissonRatio * spec.strain < 1))
    p.fail("'poissonRatio' × 'strain' must be < 1 (the width would vanish), got " +
           formatNumber(spec.poissonRatio * spec.strain));
  spec.spans = integerPair(p, "spans", "{nu, nv}", 1, kMaxSpans, ivec2(1, 1));
  checkCount(p, "'spans'", static_cast<long long>(dogboneKnotsU(spec).size()) - 4,
             spec.spans.y + 3);
  NurbsSurface surface = makeDogbone(spec);
  checked(p, [&] { validateNurbs(surface); });
  pushUserdata(L, nurbsShape(L, p, std::move(surface)));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Nurbs.from: the exact NURBS form of an analytic shape, e.g. to deform it with Nurbs.deform. The
result keeps the shape's location; its (u, v) are:

  Shape         | NURBS                                   | (u, v)
  --------------+-----------------------------------------+------------------------------------------
  Rectangle     | one Bézier patch of `degree`, evenly     | the rectangle's own: u = x/w + 1/2,
                | spaced control points                   | v = y/h + 1/2
  Box (`face`)  | the face "-z", "+x", "+z", "-x", "-y" or | the face's (s, t) in the box's 3 × 2
                | "+y" as such a patch                     | texture atlas (u = (col + s)/3, ...)
  Sphere        | rational biquadratic, 4 arcs around, 2   | the sphere's poles and seam; equal to the
                | from pole to pole (9 × 5 points)         | sphere's (u, v) every 90°, not in between
                |                                         | (a rational arc is not uniform in angle)
  Cylinder      | its side (capped = false only): 4       | the open cylinder's; u equal to it every
  (open)        | rational quadratic arcs around, cubic   | 90°, not in between; v = y/h + 1/2
                | along y (9 × 4 points)                  |

Other shapes (the infinite Plane, Triangle, a capped Cylinder) have no such form here; a NURBS is
already one.

  Parameter | Value                  | Default  | Meaning
  ----------+------------------------+----------+--------------------------------------------------
  shape     | Shape                  | required | Shape.Rectangle, Shape.Box, Shape.Sphere, an open
            |                        |          | Shape.Cylinder
  face      | string                 | required | Box only: which face
            |                        | for Box  |
  degree    | {p, q}                 | {3, 3}   | Rectangle and box faces: degrees 1..5 (flat
            |                        |          | either way; higher degrees fit smooth
            |                        |          | deformations with fewer control points)

Example: skin = Nurbs.from { shape = Shape.Sphere { radius = 0.02; location = {0, 0, 0.3} } }
------------------------------------------------------------------------------------------------ */
int nurbsFrom(lua_State* L) {
  Params p(L, "Nurbs.from", {"shape", "face", "degree"});
  const Shape* shape = p.userdata<Shape>("shape", "a Shape (Shape.Rectangle, Shape.Box, Shape.Sphere)");
  if (!shape) p.fail("missing required 'shape' (Shape.Rectangle, Shape.Box, Shape.Sphere)");
  const ivec2 degree = integerPair(p, "degree", "{p, q}", 1, kMaxNurbsDegree, {3, 3});
  const std::optional<std::string> face = p.string("face");
  if (face && shape->kind() != ShapeKind::Box) p.fail("'face' is for a Shape.Box only");
  if (p.has("degree") && shape->kind() == ShapeKind::Sphere) p.fail("'degree' is for a Rectangle or a box face (the sphere is biquadratic)");
  if (p.has("degree") && shape->kind() == ShapeKind::Cylinder) p.fail("'degree' is for a Rectangle or a box face (the cylinder is quadratic around, cubic along)");
  NurbsSurface surface;
  switch (shape->kind()) {
    case ShapeKind::Rectangle: {
      const dvec2 size = std::get<shapes::Rectangle>(shape->analytic).size_m;
      surface = makeParallelogram(dvec3(-0.5 * size.x, -0.5 * size.y, 0), dvec3(size.x, 0, 0), dvec3(0, size.y, 0), degree);
      break;
    }
    case ShapeKind::Box:
      if (!face) p.fail("missing required 'face' for a Shape.Box: \"-z\", \"+x\", \"+z\", \"-x\", \"-y\" or \"+y\"");
      checked(p, [&] { surface = makeBoxFace(std::get<shapes::Box>(shape->analytic).halfSize(), *face, degree); });
      break;
    case ShapeKind::Sphere: surface = makeSphereNurbs(std::get<shapes::Sphere>(shape->analytic).radius_m); break;
    case ShapeKind::Cylinder: {
      const auto& cylinder = std::get<shapes::Cylinder>(shape->analytic);
      if (cylinder.capped) p.fail("a capped Shape.Cylinder has no NURBS form here (its caps): give capped = false for its side");
      surface = makeCylinderSideNurbs(cylinder.radius_m, cylinder.height_m);
      break;
    }
    case ShapeKind::Plane: p.fail("a Shape.Plane is infinite: use a Shape.Rectangle"); break;
    case ShapeKind::Triangle: p.fail("a Shape.Triangle has no NURBS form here (use Shape.Nurbs with a degenerate patch)"); break;
    case ShapeKind::Nurbs: p.fail("'shape' is already a NURBS surface"); break;
    default: p.fail(std::string("a Shape.") + shapes::shapeKindInfo(shape->kind()).name + " has no NURBS form here"); break;
  }
  checked(p, [&] { validateNurbs(surface); });
  Shape result;
  result.where = LuaSandbox::of(L).here(L);
  result.location_m = shape->location_m;
  result.nurbs = std::make_shared<const NurbsSurface>(std::move(surface));
  pushUserdata(L, std::move(result));
  return 1;
}

}  // namespace

void registerNurbsConstructors(lua_State* L) {
  lua_getglobal(L, "Shape");
  DS_CHECK(lua_istable(L, -1), "registerShapeConstructors must run first");
  lua_pushcfunction(L, &protectedCall<shapeNurbs>);
  lua_setfield(L, -2, "Nurbs");
  lua_pop(L, 1);
  setConstructorTable(L, "Nurbs",
                      {{"plate", &protectedCall<nurbsPlate>},
                       {"cylinderSegment", &protectedCall<nurbsCylinderSegment>},
                       {"dogbone", &protectedCall<nurbsDogbone>},
                       {"from", &protectedCall<nurbsFrom>}});
}

}  // namespace dicsynth::scene
