// Shader.<Kind> for every reflectance model of the registry (host/reflectance/registry.h: each
// kind's home documents its parameters and formulas); Light.Point, Light.Ambient, Light.Spot (the
// radiance sum over lights: host/cpu/shading.h). docs/reflectance.md repeats the tables.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/exact_number.h"
#include "core/warning.h"
#include "scene/constructors.h"
#include "reflectance/registry.h"
#include "scene/lua_values.h"

namespace dicsynth::scene {

namespace {

// A colour parameter: gray number or {r, g, b}, each >= 0.
dvec3 readColor(const Params& p, const char* key, dvec3 fallback) {
  const dvec3 color = p.color(key).value_or(fallback);
  for (double c : {color.x, color.y, color.z}) p.require(c >= 0, key, ">= 0", c);
  return color;
}

// Shader.<Kind> for every kind of the registry: the kind's home documents and parses its own
// parameters; `color` (the diffuse albedo, its default the home's) all share.
template <class Kind>
int shaderConstructor(lua_State* L) {
  static const std::string name = std::string("Shader.") + Kind::kName;
  std::vector<const char*> keys{"color"};
  keys.insert(keys.end(), Kind::kKeys.begin(), Kind::kKeys.end());
  Params p(L, name, keys);
  Shader shader;
  shader.where = LuaSandbox::of(L).here(L);
  shader.color = readColor(p, "color", dvec3(Kind::kDefaultColor));
  // A lit shader's colour is an albedo: above 1 the surface sends back more light than falls on it.
  // Said, not refused (the image renders as asked): Shader.Lambert { color = 5 } rendered 5 times
  // the physical radiance without a word (the radiometry trial of 2026-11-29). Shader.Constant's
  // colour is a radiance, which may exceed 1. Once per constructor line (the scene runs every frame).
  if (Kind::kLit) {
    const double most = std::max({shader.color.x, shader.color.y, shader.color.z});
    if (most > 1) {
      const std::string text = shader.where.str() + ": " + name + "'s color reaches " + shortestNumber(most) +
                               ", an albedo above 1: the surface reflects more light than falls on it (brighten the "
                               "image with the lights' intensity or the camera's exposure instead)";
      warnAtMost("albedo above 1: " + text, 1, text);
    }
  }
  shader.model = Kind::parse(p);
  pushUserdata(L, std::move(shader));
  return 1;
}

// A light of `kind` at the line of its constructor call; point and spot lights with their required
// position.
Light newLight(lua_State* L, const Params& p, LightKind kind) {
  Light light;
  light.kind = kind;
  light.where = LuaSandbox::of(L).here(L);
  if (kind != LightKind::Ambient) {
    const std::optional<dvec3> position = p.vec3("position");
    if (!position) p.fail("missing required 'position' = {x, y, z} (metres)");
    // A far point light stands in for a directional one (1e6 m from a 1 m scene: parallel within
    // 1e-6 rad). Up to 1e12 m every backend was measured right (the radiometry audit of
    // 2026-11-28: fp64 4e-8, fp32/df64 4e-6 of full scale at 5.8e11 m); beyond it the fp32 path's
    // r² and intensity approach float's range. Farther was refused by prepare with a message
    // about a homography on another object's line.
    p.require(distanceFromOrigin(*position) <= kMaxDistanceFromOrigin_m, "position",
              "within 1e12 m of the origin (a nearer light with intensity scaled by distance² gives the same light)",
              distanceFromOrigin(*position));
    light.position_m = *position;
  }
  return light;
}

// Intensity of a light: a number > 0, or {r, g, b} (each >= 0) reduced to a luminance > 0.
double readIntensity(const Params& p) {
  if (p.luaType("intensity") == LUA_TTABLE) {
    const dvec3 rgb = *p.color("intensity");
    for (double c : {rgb.x, rgb.y, rgb.z}) p.require(c >= 0, "intensity", ">= 0 in r, g and b", c);
    const double value = luminance(rgb);
    p.require(value > 0, "intensity", "> 0 (its luminance)", value);
    return value;
  }
  const double value = p.number("intensity", 1.0);
  p.require(value > 0, "intensity", "> 0", value);
  return value;
}

/* ------------------------------------------------------------------------------------------------
Light.Point: an isotropic point light. Only lights assigned to global variables are used.

  Parameter | Value                    | Default  | Meaning
  ----------+--------------------------+----------+-----------------------------------------------
  position  | {x, y, z}, m             | required | where the light is
  intensity | number or {r, g, b}      | 1        | radiant intensity I (radiance units * m²), > 0;
            |                          |          | RGB is reduced to its Rec. 709 luminance

Example:  lamp = Light.Point { position = {0.2, -0.3, 0}; intensity = 0.05 }
------------------------------------------------------------------------------------------------ */
int lightPoint(lua_State* L) {
  Params p(L, "Light.Point", {"position", "intensity"});
  Light light = newLight(L, p, LightKind::Point);
  light.intensity = readIntensity(p);
  pushUserdata(L, std::move(light));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Light.Ambient: light of radiance L_a arriving equally from every direction, never shadowed. It adds
ρ · L_a to the radiance of every lit (non-Constant) surface: the diffuse part only (ρ = albedo ×
texture; a Lambertian surface under uniform radiance L_a has irradiance π L_a, hence radiance
ρ/π · π L_a). Specular lobes ignore it.

  Parameter | Value                    | Default  | Meaning
  ----------+--------------------------+----------+-----------------------------------------------
  intensity | number or {r, g, b}      | 1        | incident radiance L_a (radiance units), > 0

Example:  sky = Light.Ambient { intensity = 0.05 }
------------------------------------------------------------------------------------------------ */
int lightAmbient(lua_State* L) {
  Params p(L, "Light.Ambient", {"intensity"});
  Light light = newLight(L, p, LightKind::Ambient);
  light.intensity = readIntensity(p);
  pushUserdata(L, std::move(light));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Light.Spot: a point light whose intensity I·s(φ) falls off with the angle φ from its axis: s = 1
within innerAngle, 0 beyond outerAngle, and between them the smoothstep t²(3 − 2t) of
t = (cos φ − cos outer)/(cos inner − cos outer) (defined on cos φ, host/cpu/shading.h).

  Parameter  | Value                    | Default  | Meaning
  -----------+--------------------------+----------+----------------------------------------------
  position   | {x, y, z}, m             | required | where the light is
  direction  | {x, y, z}                |          | the cone's axis (any length > 0), or
  lookAt     | {x, y, z}, m             |          | a point on the axis; exactly one of the two
  intensity  | number or {r, g, b}      | 1        | radiant intensity I on the axis, > 0
  innerAngle | rad                      | 0        | half-angle of full intensity, >= 0
  outerAngle | rad                      | required | half-angle beyond which it is dark, in
             |                          |          | (innerAngle, π]

Example:  spot = Light.Spot { position = {0, -0.3, 0}; lookAt = {0, 0, 0.5};
                              innerAngle = degrees(10); outerAngle = degrees(20); intensity = 0.1 }
------------------------------------------------------------------------------------------------ */
int lightSpot(lua_State* L) {
  Params p(L, "Light.Spot", {"position", "direction", "lookAt", "intensity", "innerAngle", "outerAngle"});
  Light light = newLight(L, p, LightKind::Spot);
  const std::optional<dvec3> direction = p.vec3("direction"), lookAt = p.vec3("lookAt");
  if (direction.has_value() == lookAt.has_value())
    p.fail("give exactly one of 'direction' = {x, y, z} and 'lookAt' = {x, y, z} (metres)");
  light.direction = direction ? *direction : *lookAt - light.position_m;
  const double length = glm::length(light.direction);
  if (!(length > 0))
    p.fail(direction ? "'direction' must not be the zero vector" : "'lookAt' must differ from 'position'");
  light.direction /= length;
  light.intensity = readIntensity(p);
  light.innerAngle_rad = p.number("innerAngle", 0.0);
  p.requireAngle(light.innerAngle_rad >= 0, "innerAngle", ">= 0 (radians)", light.innerAngle_rad);
  if (!p.has("outerAngle")) p.fail("missing required 'outerAngle' (radians)");
  light.outerAngle_rad = p.requiredNumber("outerAngle");
  p.requireAngle(light.outerAngle_rad > light.innerAngle_rad && light.outerAngle_rad <= kPi, "outerAngle",
            "in (innerAngle, pi] (radians)", light.outerAngle_rad);
  pushUserdata(L, std::move(light));
  return 1;
}

int shaderToString(lua_State* L) {
  const Shader* shader = toUserdata<Shader>(L, 1);
  lua_pushfstring(L, "Shader.%s", shader ? reflectance::kindInfo(shader->model).name : "?");
  return 1;
}

int lightToString(lua_State* L) {
  const Light* light = toUserdata<Light>(L, 1);
  const LightKind kind = light ? light->kind : LightKind::Point;
  lua_pushstring(L, kind == LightKind::Ambient ? "Light.Ambient" : kind == LightKind::Spot ? "Light.Spot" : "Light.Point");
  return 1;
}

}  // namespace

void registerShadingConstructors(lua_State* L) {
  registerUserdataType<Shader>(L, {{"__tostring", &shaderToString}});
  registerUserdataType<Light>(L, {{"__tostring", &lightToString}});
  std::vector<luaL_Reg> constructors;
  reflectance::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    constructors.push_back({Kind::kName, &protectedCall<shaderConstructor<Kind>>});
  });
  setConstructorTable(L, "Shader", constructors);
  setConstructorTable(L, "Light",
                      {{"Point", &protectedCall<lightPoint>},
                       {"Ambient", &protectedCall<lightAmbient>},
                       {"Spot", &protectedCall<lightSpot>}});
}

}  // namespace dicsynth::scene
