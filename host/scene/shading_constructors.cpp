// Shader.Constant, Shader.Lambert, Shader.Phong, Shader.BlinnPhong, Shader.GGX; Light.Point,
// Light.Ambient, Light.Spot. The formulas are in host/cpu/shading.h; the README repeats the tables.
#include <cmath>
#include <string>

#include "scene/constructors.h"
#include "scene/lua_values.h"

namespace dicsynth::scene {

namespace {

constexpr int kMaxShininess = 10000;  // x^n by repeated squaring: ≤ 28 products (cpu/shading.h)
// GGX's D peaks at 1/(πα²) with a relative slope 4/α² in cos θh: below α = 0.01 a highlight is a
// near-mirror image of the light, hundreds of times full scale, whose rounding-level differences
// (the hit position's 1e-15 relative between backends, through that slope) exceed the fp64 GPU
// variant's 1e-9 of full scale (measured: 3.5e-8 at α = 0.001). Polished metals are α ≈ 0.01-0.05.
constexpr double kMinRoughness = 0.01;

// A colour parameter: gray number or {r, g, b}, each >= 0.
dvec3 readColor(const Params& p, const char* key, dvec3 fallback) {
  const dvec3 color = p.color(key).value_or(fallback);
  for (double c : {color.x, color.y, color.z}) p.require(c >= 0, key, ">= 0", c);
  return color;
}

// A number in [lo, hi], or the luminance of {r, g, b} with each component there.
double readGray(const Params& p, const char* key, double fallback, double lo, double hi, const char* range) {
  double value = fallback;
  if (p.luaType(key) == LUA_TTABLE) {
    const dvec3 rgb = *p.color(key);
    for (double c : {rgb.x, rgb.y, rgb.z}) p.require(c >= lo && c <= hi, key, range, c);
    value = luminance(rgb);
  } else {
    value = p.number(key, fallback);
  }
  p.require(value >= lo && value <= hi, key, range, value);
  return value;
}

const char* shaderName(ShaderKind kind) {
  switch (kind) {
    case ShaderKind::Constant: return "Shader.Constant";
    case ShaderKind::Lambert: return "Shader.Lambert";
    case ShaderKind::Phong: return "Shader.Phong";
    case ShaderKind::BlinnPhong: return "Shader.BlinnPhong";
    case ShaderKind::Ggx: return "Shader.GGX";
  }
  return "Shader";
}

/* ------------------------------------------------------------------------------------------------
Shader.Constant: the surface shows its colour times the texture, lit or not (no lights needed).
Shader.Lambert:  an ideal diffuse surface lit by the scene's lights; color is the albedo.

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+---------------------------------------
  color     | {r, g, b} or gray number  | {1, 1, 1}  | linear RGB, each >= 0; the grayscale
            |                           |            | sensor sees its Rec. 709 luminance

Example:  Shader.Constant { color = {.2, .8, 1} }      Shader.Lambert { color = 0.7 }
------------------------------------------------------------------------------------------------ */
template <ShaderKind Kind>
int shader(lua_State* L) {
  Params p(L, shaderName(Kind), {"color"});
  Shader shader;
  shader.kind = Kind;
  shader.where = LuaSandbox::of(L).here(L);
  shader.color = readColor(p, "color", dvec3(1));
  pushUserdata(L, std::move(shader));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Shader.Phong, Shader.BlinnPhong: Lambert's diffuse part (textured) plus an energy-normalized
specular lobe (not textured), f = ρ/π + f_spec:
  Phong:       f_spec = specular · (n + 2)/(2π) · max(0, R·V)^n   (R: mirror direction of the light)
  BlinnPhong:  f_spec = specular · (n + 8)/(8π) · max(0, N·H)^n   (H: half vector of light and view)

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+------------------------------------------
  color     | {r, g, b} or gray number  | {1, 1, 1}  | diffuse albedo ρ (luminance), × texture
  specular  | number >= 0               | 0.1        | ks, weight of the lobe (ρ + ks <= 1
            |                           |            | conserves energy at normal view)
  shininess | integer in [1, 10000]     | 50         | n: larger, smaller highlight (integer:
            |                           |            | GPU x^n by repeated squaring, exact)

Example:  Shader.Phong { color = 0.6; specular = 0.3; shininess = 80 }
------------------------------------------------------------------------------------------------ */
template <ShaderKind Kind>
int shaderPhong(lua_State* L) {
  Params p(L, shaderName(Kind), {"color", "specular", "shininess"});
  Shader shader;
  shader.kind = Kind;
  shader.where = LuaSandbox::of(L).here(L);
  shader.color = readColor(p, "color", dvec3(1));
  shader.specular = p.number("specular", 0.1);
  p.require(shader.specular >= 0, "specular", ">= 0", shader.specular);
  const double n = p.number("shininess", 50);
  p.require(n == std::floor(n) && n >= 1 && n <= kMaxShininess, "shininess", "an integer in [1, 10000]", n);
  shader.shininess = int(n);
  pushUserdata(L, std::move(shader));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Shader.GGX: Cook-Torrance microfacet reflection for metals, f = ρ/π + D·F·G₂/(4 cosθi cosθo) with
the GGX (Trowbridge-Reitz) distribution D of width α, Schlick's Fresnel F from F0 and the
height-correlated Smith masking-shadowing G₂ (formulas: host/cpu/shading.h). The diffuse part ρ
(× texture) is 0 by default: a bare metal; give `color` for paint (a speckle) on a metal.

  Parameter | Value                     | Default    | Meaning
  ----------+---------------------------+------------+------------------------------------------
  color     | {r, g, b} or gray number  | 0          | diffuse albedo ρ (luminance), × texture
  roughness | number in [0.01, 1]       | 0.3        | α (the "perceptual roughness" squared)
  f0        | number or {r, g, b}, each | 0.56       | Fresnel reflectance at normal incidence
            | in [0, 1]                 |            | (luminance): steel 0.56, aluminium 0.91

Example:  Shader.GGX { roughness = 0.2; f0 = 0.91 }
------------------------------------------------------------------------------------------------ */
int shaderGgx(lua_State* L) {
  Params p(L, "Shader.GGX", {"color", "roughness", "f0"});
  Shader shader;
  shader.kind = ShaderKind::Ggx;
  shader.where = LuaSandbox::of(L).here(L);
  shader.color = readColor(p, "color", dvec3(0));
  shader.roughness = p.number("roughness", 0.3);
  p.require(shader.roughness >= kMinRoughness && shader.roughness <= 1, "roughness", "in [0.01, 1]",
            shader.roughness);
  shader.f0 = readGray(p, "f0", 0.56, 0, 1, "in [0, 1]");
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
  p.require(light.innerAngle_rad >= 0, "innerAngle", ">= 0 (radians)", light.innerAngle_rad);
  if (!p.has("outerAngle")) p.fail("missing required 'outerAngle' (radians)");
  light.outerAngle_rad = p.requiredNumber("outerAngle");
  p.require(light.outerAngle_rad > light.innerAngle_rad && light.outerAngle_rad <= kPi, "outerAngle",
            "in (innerAngle, pi] (radians)", light.outerAngle_rad);
  pushUserdata(L, std::move(light));
  return 1;
}

int shaderToString(lua_State* L) {
  const Shader* shader = toUserdata<Shader>(L, 1);
  lua_pushstring(L, shaderName(shader ? shader->kind : ShaderKind::Constant));
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
  setConstructorTable(L, "Shader",
                      {{"Constant", &protectedCall<shader<ShaderKind::Constant>>},
                       {"Lambert", &protectedCall<shader<ShaderKind::Lambert>>},
                       {"Phong", &protectedCall<shaderPhong<ShaderKind::Phong>>},
                       {"BlinnPhong", &protectedCall<shaderPhong<ShaderKind::BlinnPhong>>},
                       {"GGX", &protectedCall<shaderGgx>}});
  setConstructorTable(L, "Light",
                      {{"Point", &protectedCall<lightPoint>},
                       {"Ambient", &protectedCall<lightAmbient>},
                       {"Spot", &protectedCall<lightSpot>}});
}

}  // namespace dicsynth::scene
