// Shape.Sphere, Shape.Box, Shape.Rectangle, Shape.Plane, Shape.Triangle (Shape.Nurbs and the
// Nurbs.* specimens: nurbs_constructors.cpp).
// Every shape is defined in its own frame; `location` (metres, default {0, 0, 0}) places that
// frame's origin in the object's frame. An Object's transform is applied about the location
// (worldFromShape = translate(location) * transform, see scene.h).
#include <algorithm>

#include "model/shape_kinds.h"
#include "scene/constructors.h"
#include "scene/lua_values.h"

namespace dicsynth::scene {

namespace {

Shape newShape(lua_State* L, const Params& p, ShapeKind kind) {
  Shape shape;
  shape.kind = kind;
  shape.where = LuaSandbox::of(L).here(L);
  shape.location_m = p.vec3("location").value_or(dvec3(0));
  return shape;
}

/* ------------------------------------------------------------------------------------------------
Shape.Sphere: a sphere centred on `location`.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+------------------------------
  radius    | number, m      | required  | > 0
  location  | {x, y, z}, m   | {0, 0, 0} | centre in the object's frame

Example:  Shape.Sphere { radius = 0.1; location = {0, 0, 0.5} }
------------------------------------------------------------------------------------------------ */
int shapeSphere(lua_State* L) {
  Params p(L, "Shape.Sphere", {"radius", "location"});
  Shape shape = newShape(L, p, ShapeKind::Sphere);
  shape.radius_m = p.requiredNumber("radius");
  p.require(shape.radius_m > 0, "radius", "> 0 (metres)", shape.radius_m);
  pushUserdata(L, std::move(shape));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Shape.Box: a rectangular box with edges along the axes of its frame, whose origin is `location`.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+---------------------------------------
  size      | {sx, sy, sz}, m| required  | full edge lengths along x, y, z; > 0
  location  | {x, y, z}, m   | {0, 0, 0} | origin of the box's frame

Example:  Shape.Box { size = {0.2, 0.1, 0.01} }
------------------------------------------------------------------------------------------------ */
int shapeBox(lua_State* L) {
  Params p(L, "Shape.Box", {"size", "location"});
  Shape shape = newShape(L, p, ShapeKind::Box);
  auto size = p.vec3("size", "{sx, sy, sz}");
  if (!size) p.fail("missing required 'size' = {sx, sy, sz} (metres)");
  for (double s : {size->x, size->y, size->z})
    p.require(s > 0, "size", "> 0 (metres) in x, y and z", s);
  shape.size_m = *size;
  pushUserdata(L, std::move(shape));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Shape.Rectangle: a flat rectangle in the xy-plane of its frame, whose origin is `location`.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+-----------------------------------
  size      | {w, h}, m      | required  | extent along x and y; > 0
  location  | {x, y, z}, m   | {0, 0, 0} | origin of the rectangle's frame

Example:  Shape.Rectangle { size = {0.2, 0.1}; location = {0, 0, 0.5} }
------------------------------------------------------------------------------------------------ */
int shapeRectangle(lua_State* L) {
  Params p(L, "Shape.Rectangle", {"size", "location"});
  Shape shape = newShape(L, p, ShapeKind::Rectangle);
  auto size = p.vec2("size", "{w, h}");
  if (!size) p.fail("missing required 'size' = {w, h} (metres)");
  for (double s : {size->x, size->y}) p.require(s > 0, "size", "> 0 (metres) in w and h", s);
  shape.size_m = dvec3(*size, 0);
  pushUserdata(L, std::move(shape));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Shape.Plane: the infinite xy-plane of its frame; the texture repeats every tile.

  Parameter | Value          | Default   | Meaning
  ----------+----------------+-----------+-------------------------------------------
  tileSize  | {w, h}, m      | {1, 1}    | (u, v) run over [0, 1] once per tile; > 0
  location  | {x, y, z}, m   | {0, 0, 0} | origin of the plane's frame

Example:  Shape.Plane { tileSize = {0.05, 0.05}; location = {0, 0, 1} }
------------------------------------------------------------------------------------------------ */
int shapePlane(lua_State* L) {
  Params p(L, "Shape.Plane", {"tileSize", "location"});
  Shape shape = newShape(L, p, ShapeKind::Plane);
  const dvec2 tile = p.vec2("tileSize", "{w, h}").value_or(dvec2(1, 1));
  for (double s : {tile.x, tile.y}) p.require(s > 0, "tileSize", "> 0 (metres) in w and h", s);
  shape.size_m = dvec3(tile, 0);
  pushUserdata(L, std::move(shape));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Shape.Triangle: one triangle; its vertices are relative to `location`.

  Parameter | Value                            | Default               | Meaning
  ----------+----------------------------------+-----------------------+------------------------
  vertices  | {{x, y, z}, {x, y, z}, {x, y, z}}| required              | corners, metres; must
            |                                  |                       | span a real triangle
  uv        | {{u, v}, {u, v}, {u, v}}         | {{0, 0}, {1, 0},      | texture coordinates of
            |                                  |  {0, 1}}              | the corners
  location  | {x, y, z}, m                     | {0, 0, 0}             | offset of all corners

Degenerate triangles are refused: |cross(v1 - v0, v2 - v0)| must exceed 1e-12 * (longest edge)².

Example:  Shape.Triangle { vertices = {{0, 0, 1}, {0.1, 0, 1}, {0, 0.1, 1}} }
------------------------------------------------------------------------------------------------ */
int shapeTriangle(lua_State* L) {
  Params p(L, "Shape.Triangle", {"vertices", "uv", "location"});
  Shape shape = newShape(L, p, ShapeKind::Triangle);
  auto vertices = p.tables("vertices", 3, 3, "{{x, y, z}, {x, y, z}, {x, y, z}}");
  if (!vertices) p.fail("missing required 'vertices' = {{x, y, z}, {x, y, z}, {x, y, z}}");
  for (int i = 0; i < 3; ++i)
    shape.vertices_m[i] = dvec3((*vertices)[i][0], (*vertices)[i][1], (*vertices)[i][2]);
  if (auto uv = p.tables("uv", 3, 2, "{{u, v}, {u, v}, {u, v}}"))
    for (int i = 0; i < 3; ++i) shape.vertexUV[i] = dvec2((*uv)[i][0], (*uv)[i][1]);

  // Refuse degenerate triangles, relative to the triangle's own size.
  const auto& v = shape.vertices_m;
  const double longest =
      std::max({glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2])});
  const double twiceArea = glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
  if (!(twiceArea > 1e-12 * longest * longest))
    p.fail("'vertices' must span a triangle, but they are coincident or collinear");
  pushUserdata(L, std::move(shape));
  return 1;
}

int shapeToString(lua_State* L) {
  const Shape* shape = toUserdata<Shape>(L, 1);
  lua_pushfstring(L, "Shape.%s", shape ? shapeKindInfo(shape->kind).name : "?");
  return 1;
}

}  // namespace

void registerShapeConstructors(lua_State* L) {
  registerUserdataType<Shape>(L, {{"__tostring", &shapeToString}});
  setConstructorTable(L, "Shape",
                      {{"Sphere", &protectedCall<shapeSphere>},
                       {"Box", &protectedCall<shapeBox>},
                       {"Rectangle", &protectedCall<shapeRectangle>},
                       {"Plane", &protectedCall<shapePlane>},
                       {"Triangle", &protectedCall<shapeTriangle>}});
}

}  // namespace dicsynth::scene
