#pragma once
// The scene language: constructors (Camera.Pinhole { ... }, Shape.Sphere { ... }, ...) and
// transform functions (translate, rotate_y, ...) as Lua globals. One file per category; each
// constructor's user documentation sits at the top of the code that reads its parameters.
struct lua_State;

namespace dicsynth::scene {

// Registers every userdata type and sets all globals of the scene language.
void registerSceneLanguage(lua_State* L);

void registerCameraConstructors(lua_State* L);  // camera_constructors.cpp: Camera, Distortion
void registerShapeConstructors(lua_State* L);   // shape_constructors.cpp: Shape
void registerNurbsConstructors(lua_State* L);   // nurbs_constructors.cpp: Shape.Nurbs, Nurbs
                                                //   (after registerShapeConstructors)
void registerObjectConstructors(lua_State* L);  // object_constructors.cpp: Shader, Texture,
                                                //   Object, Light
void registerTransformFunctions(lua_State* L);  // transform_functions.cpp: translate, ...
void registerTargetConstructors(lua_State* L);  // target_constructors.cpp: Target (after
                                                //   registerObjectConstructors)
void registerSweepFunctions(lua_State* L);      // sweep_functions.cpp: linspace, points, random
void registerRigConstructors(lua_State* L);     // rig_constructors.cpp: Rig

}  // namespace dicsynth::scene
