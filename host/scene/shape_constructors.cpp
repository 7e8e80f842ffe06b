// Shape.<Kind> for every analytic kind of the registry (host/shapes/registry.h): each kind's home
// documents and parses its parameters; this file adds what all share and binds them to Lua.
// Shape.Nurbs and the Nurbs.* specimens: nurbs_constructors.cpp.
// Every shape is defined in its own frame; `location` (metres, default {0, 0, 0}) places that
// frame's origin in the object's frame. An Object's transform is applied about the location
// (worldFromShape = translate(location) * transform, see scene.h).
#include <string>
#include <vector>

#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "shapes/registry.h"

namespace dicsynth::scene {

namespace {

template <class Kind>
int shapeConstructor(lua_State* L) {
  static const std::string name = std::string("Shape.") + Kind::kName;
  std::vector<const char*> keys(std::begin(Kind::kKeys), std::end(Kind::kKeys));
  keys.push_back("location");
  Params p(L, name, keys);
  Shape shape;
  shape.where = LuaSandbox::of(L).here(L);
  shape.location_m = p.vec3("location").value_or(dvec3(0));
  // As a light's position: beyond, a plane's (u, v) overflowed to NaN, which the texture lookup
  // cast to int (undefined behaviour, found by the sanitizer run of 2026-11-28 on a fuzz mutant
  // with location -1e308), and the run ended on a misleading "radiance is nan".
  const double distance = distanceFromOrigin(shape.location_m);
  p.require(distance <= kMaxDistanceFromOrigin_m, "location", "within 1e12 m of the origin", distance);
  shape.analytic = Kind::parse(p);
  pushUserdata(L, std::move(shape));
  return 1;
}

int shapeToString(lua_State* L) {
  const Shape* shape = toUserdata<Shape>(L, 1);
  lua_pushfstring(L, "Shape.%s", shape ? shapes::shapeKindInfo(shape->kind()).name : "?");
  return 1;
}

}  // namespace

void registerShapeConstructors(lua_State* L) {
  registerUserdataType<Shape>(L, {{"__tostring", &shapeToString}});
  std::vector<luaL_Reg> constructors;
  shapes::forEachAnalyticKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    constructors.push_back({Kind::kName, &protectedCall<shapeConstructor<Kind>>});
  });
  setConstructorTable(L, "Shape", constructors);
}

}  // namespace dicsynth::scene
