#pragma once
// The scene language: constructors (Camera.Pinhole { ... }, Shape.Sphere { ... }, ...) and
// transform functions (translate, rotate_y, ...) as Lua globals. One file per category; each
// constructor's user documentation sits at the top of the code that reads its parameters (or in
// the kind's home: host/shapes, host/reflectance).
#include <algorithm>
#include <cmath>
#include <string>

#include "core/math.h"
#include "reflectance/registry.h"

struct lua_State;

namespace dicsynth::scene {

// How far from the world origin a light's position and a shape's location may lie (m): beyond, the
// fp32 path's r² nears float's range, and an infinite plane's (u, v) overflowed to NaN.
inline constexpr double kMaxDistanceFromOrigin_m = 1e12;

// |p| without overflow to inf (scaled by its largest component), so that a refusal names the
// distance given: glm::length({-1e308, 0, 0}) is inf.
inline double distanceFromOrigin(const dvec3& p) {
  const double largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return largest > 0 ? largest * glm::length(p / largest) : 0;
}

// Registers every userdata type and sets all globals of the scene language.
void registerSceneLanguage(lua_State* L);

void registerCameraConstructors(lua_State* L);  // camera_constructors.cpp: Camera, Distortion
void registerShapeConstructors(lua_State* L);   // shape_constructors.cpp: Shape
void registerNurbsConstructors(lua_State* L);   // nurbs_constructors.cpp: Shape.Nurbs, Nurbs
                                                //   (after registerShapeConstructors)
void registerDeformConstructors(lua_State* L); // deform_constructors.cpp: Field, Nurbs.deform
                                                //   (after registerNurbsConstructors)
void registerObjectConstructors(lua_State* L);  // object_constructors.cpp: Texture, Object
void registerShadingConstructors(lua_State* L); // shading_constructors.cpp: Shader, Light
void registerTransformFunctions(lua_State* L);  // transform_functions.cpp: translate, ...
void registerTargetConstructors(lua_State* L);  // target_constructors.cpp: Target (after
                                                //   registerObjectConstructors)
void registerSweepFunctions(lua_State* L);      // sweep_functions.cpp: linspace, points, random
void registerRigConstructors(lua_State* L);     // rig_constructors.cpp: Rig
void registerSensorConstructors(lua_State* L);  // sensor_constructors.cpp: Sensor, Blur,
                                                //   Vignetting, Dust, DefectivePixels

// What a 'shader' parameter must be, for error messages: every model of the registry
// (host/reflectance/registry.h), in number order.
inline const char* shaderExpected() {
  static const std::string text = [] {
    std::string list;
    for (const reflectance::KindInfo& k : reflectance::kKinds) list += std::string(list.empty() ? "" : ", ") + "Shader." + k.name;
    return "a Shader (" + list + ")";
  }();
  return text.c_str();
}

}  // namespace dicsynth::scene
