// Shape.Nurbs. Like every shape, a NURBS surface is defined in its own frame; `location` places
// that frame's origin (the control points are relative to it), and an Object's transform acts
// about the location (worldFromShape = translate(location) * transform).

#include <cmath>
#include <memory>
#include <tuple>

#include "scene/constructors.h"
#include "scene/lua_values.h"

namespace dicsynth::scene {

namespace {

Shape nurbsShape(lua_State* L, const Params& p, NurbsSurface surface) {
  Shape shape;
  shape.kind = ShapeKind::Nurbs;
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
  weights       | {w1, w2, ...}       | all 1     | one per control point, same order; > 0
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
  const std::string countText = "countU × countV = " + std::to_string(s.countU) + " × " +
                                std::to_string(s.countV) + " = " + std::to_string(count);
  auto points = p.vec3List("controlPoints", count, countText);
  if (!points) p.fail("missing required 'controlPoints' = {{x, y, z}, ...} (" + countText + ")");
  s.controlPoints = std::move(*points);
  s.weights = p.numbers("weights", count, count, "{w1, w2, ...}, one per control point")
                  .value_or(std::vector<double>(count, 1.0));
  checked(p, [&] { validateNurbs(s); });
  pushUserdata(L, nurbsShape(L, p, std::move(s)));
  return 1;
}

}  // namespace

void registerNurbsConstructors(lua_State* L) {
  lua_getglobal(L, "Shape");
  DS_CHECK(lua_istable(L, -1), "registerShapeConstructors must run first");
  lua_pushcfunction(L, &protectedCall<shapeNurbs>);
  lua_setfield(L, -2, "Nurbs");
  lua_pop(L, 1);
}

}  // namespace dicsynth::scene
