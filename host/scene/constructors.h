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
