// The texture value of an object at (u, v), dispatched to each kind's GLSL twin
// (shaders/textures/<twin>.glsl ↔ host/textures/<kind>.h). Expects the including shader to declare
// `textures[]` (GpuTexture), DS_TEXEL(i) (coefficient i, a real), DS_OBJECT(i, member) and
// DS_OBJECT_H(i, member) (member of GpuObject i), and to include lib/features.glsl.
// ds_object_texture() is the one entry point the shading calls.
#ifndef DS_TEXTURE_GLSL
#define DS_TEXTURE_GLSL
#include "lib/real.glsl"
#include "shared/kinds.h"
#include "shared/rng.h"

// The registry of texture kinds on the GPU (host/textures/registry.h is the C++ one): each row is
// a twin, the specialization test that compiles it in, and the kinds it draws (the two targets
// share one). Texture.Constant has no twin: its value is GpuObject.shading.y.
#include "textures/file.glsl"
#include "textures/speckle.glsl"
#include "textures/target.glsl"
#define DS_TEXTURES(X)                                                                  \
  X(file, HAS_FILE_TEXTURES, kind == DS_TEXTURE_FILE)                                   \
  X(target, true, kind == DS_TEXTURE_CHECKERBOARD || kind == DS_TEXTURE_CIRCLE_GRID)    \
  X(speckle, HAS_SPECKLE_TEXTURES, kind == DS_TEXTURE_SPECKLE)

// The texture value (multiplies the shader's colour) of an object at (u, v): the one entry point
// of the shading (lib/trace.glsl), the twin of textures::at() in host/textures/registry.h.
real ds_object_texture(int object, hreal2 uv) {
  const int kind = DS_OBJECT(object, extra).y;
#define DS_TEXTURE_CASE(twin, compiled, drawn) \
  if (compiled && (drawn)) return ds_##twin##_value(ds_##twin##_data(object), uv);
  DS_TEXTURES(DS_TEXTURE_CASE)
#undef DS_TEXTURE_CASE
  return DS_OBJECT(object, shading).y;  // Texture.Constant
}

#endif
