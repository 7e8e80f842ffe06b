// Specialization constants: the host switches off what a scene does not use, and the driver's
// compiler removes that code (docs/design.md §5). Defaults are "on", so an unspecialized pipeline is
// always correct.
#ifndef DS_FEATURES_GLSL
#define DS_FEATURES_GLSL
#include "shared/bindings.h"
layout(constant_id = DS_SPEC_HAS_LIGHTS) const bool HAS_LIGHTS = true;
layout(constant_id = DS_SPEC_HAS_DISTORTION) const bool HAS_DISTORTION = true;
layout(constant_id = DS_SPEC_HAS_FILE_TEXTURES) const bool HAS_FILE_TEXTURES = true;
layout(constant_id = DS_SPEC_HAS_SPECKLE_TEXTURES) const bool HAS_SPECKLE_TEXTURES = true;
layout(constant_id = DS_SPEC_HAS_QUINTIC_TEXTURES) const bool HAS_QUINTIC_TEXTURES = true;
layout(constant_id = DS_SPEC_HAS_TARGET_TEXTURES) const bool HAS_TARGET_TEXTURES = true;
// Shape kinds present: the intersection switch keeps only their cases. Matters on SIMD devices,
// which otherwise run every case of a switch whose value they cannot prove uniform.
layout(constant_id = DS_SPEC_SHAPE_KINDS) const uint SHAPE_KINDS = 0xffffffffu;
#define DS_HAS_SHAPE(kind) ((SHAPE_KINDS & (1u << (kind))) != 0u)
// The NURBS search is most of the module (bench/RESULTS.md, "Render modules without the NURBS
// search"), and lavapipe translates and optimizes all of it on every pipeline creation, specialized
// out or not: CMake also builds each variant with DS_NO_NURBS, which scenes without NURBS use
// (host/gpu/renderer.cpp, renderSpirv).
#if defined(DS_NO_NURBS)
#define DS_HAS_NURBS false
#else
#define DS_HAS_NURBS DS_HAS_SHAPE(DS_SHAPE_NURBS)
#endif
// Every NURBS patch of the scene arrives raised to this degree in u and v (host/gpu/pack.cpp), so
// the patch loops have constant bounds: unrolled, the control points stay in registers.
layout(constant_id = DS_SPEC_NURBS_DEGREE) const int NURBS_DEGREE = 3;
// Camera kinds present (bit k: DS_CAMERA_* k) and OpenCV's rational/thin-prism distortion terms: a
// scene of pinhole cameras with Brown (or no) distortion compiles neither lens sampling nor them.
layout(constant_id = DS_SPEC_CAMERA_KINDS) const uint CAMERA_KINDS = 0xffffffffu;
layout(constant_id = DS_SPEC_HAS_RATIONAL_DISTORTION) const bool HAS_RATIONAL_DISTORTION = true;
// Shader and light kinds present (lib/shading.glsl): a Lambert-only scene compiles no specular code
// (HAS_SPECULAR, defined there from its registry of lobes).
layout(constant_id = DS_SPEC_SHADER_KINDS) const uint SHADER_KINDS = 0xffffffffu;
layout(constant_id = DS_SPEC_LIGHT_KINDS) const uint LIGHT_KINDS = 0xffffffffu;
#define DS_HAS_SHADER(kind) ((SHADER_KINDS & (1u << (kind))) != 0u)
#define DS_HAS_LIGHT(kind) ((LIGHT_KINDS & (1u << (kind))) != 0u)
// Where the scene's data is read from (shared/bindings.h, render.comp) and how many objects and
// lights the loops run over: a count > 0 (objects) or >= 0 (lights) is exact and unrolls the loops.
layout(constant_id = DS_SPEC_UNIFORM_SCENE) const bool UNIFORM_SCENE = false;
layout(constant_id = DS_SPEC_TEXEL_VIEW) const bool TEXEL_VIEW = false;
layout(constant_id = DS_SPEC_OBJECT_COUNT) const int OBJECT_COUNT = 0;
layout(constant_id = DS_SPEC_LIGHT_COUNT) const int LIGHT_COUNT = -1;
// CPU devices: the objects (and lights) of an exact count are read from per-invocation copies
// (render.comp, LOCAL_SCENE).
layout(constant_id = DS_SPEC_LOCAL_SCENE) const bool LOCAL_SCENE = false;
#endif
