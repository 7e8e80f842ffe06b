// Closed lists of kinds, shared by C++ (host) and GLSL (shaders). Values are stored in GPU buffers:
// never renumber. A shape, reflectance model, texture or camera kind has a home
// (host/<folder>/<file>.h, and a GLSL twin shaders/<folder>/<file>.glsl where it needs one) and a
// row in its family's X-list below, from which both registries are built (docs/design.md §7).
#ifndef DS_SHARED_KINDS_H
#define DS_SHARED_KINDS_H

#define DS_SHAPE_SPHERE 0
#define DS_SHAPE_BOX 1
#define DS_SHAPE_TRIANGLE 2
#define DS_SHAPE_PLANE 3
#define DS_SHAPE_RECTANGLE 4
#define DS_SHAPE_NURBS 5
#define DS_SHAPE_CYLINDER 6
#define DS_SHAPE_COUNT 7

// Each family's kinds, one row each: X(number, C++ type, file), the file naming the kind's home
// host/<folder>/<file>.h (struct <Type> in the family's namespace) and, where it has one, its GLSL
// twin shaders/<folder>/<file>.glsl. The C++ registries (host/<folder>/registry.h) build their
// variant from these rows, in this order; cmake/KindRegistry.cmake reads them (the only
// "X(DS_<FAMILY>_" text here) to generate the includes of the homes and twins and each GLSL
// registry's lists of twins (DS_<FAMILY>_TWINS; DS_<FAMILY>_TWIN_FILES with the kinds each
// draws), and the C++ enums below take their enumerators from them. A new kind is its number
// above, its row here, its home, its twin and its test (docs/design.md §7).
// Analytic shapes (every kind but NURBS; each has a twin: Gpu<Type>, ds_<file>_data,
// ds_<file>_search, ds_<file>_attributes).
#define DS_ANALYTIC_SHAPES(X)                \
  X(DS_SHAPE_SPHERE, Sphere, sphere)          \
  X(DS_SHAPE_BOX, Box, box)                   \
  X(DS_SHAPE_TRIANGLE, Triangle, triangle)    \
  X(DS_SHAPE_PLANE, Plane, plane)             \
  X(DS_SHAPE_RECTANGLE, Rectangle, rectangle) \
  X(DS_SHAPE_CYLINDER, Cylinder, cylinder)

#define DS_SHADER_CONSTANT 0
#define DS_SHADER_LAMBERT 1
#define DS_SHADER_PHONG 2
#define DS_SHADER_BLINN_PHONG 3
#define DS_SHADER_GGX 4
#define DS_SHADER_COUNT 5

// Reflectance models; a twin is a specular lobe (Gpu<Type>, ds_<file>_data, ds_<file>_lobe).
#define DS_REFLECTANCE_MODELS(X)                      \
  X(DS_SHADER_CONSTANT, Constant, constant)          \
  X(DS_SHADER_LAMBERT, Lambert, lambert)             \
  X(DS_SHADER_PHONG, Phong, phong)                   \
  X(DS_SHADER_BLINN_PHONG, BlinnPhong, blinn_phong)  \
  X(DS_SHADER_GGX, Ggx, ggx)

#define DS_TEXTURE_CONSTANT 0
#define DS_TEXTURE_FILE 1
#define DS_TEXTURE_CHECKERBOARD 2  // calibration targets, drawn analytically (texture/target_texture.h)
#define DS_TEXTURE_CIRCLE_GRID 3
#define DS_TEXTURE_SPECKLE 4  // analytic Boolean-model speckle in (u, v) (texture/analytic_speckle.h)
#define DS_TEXTURE_COUNT 5

// Textures; a twin draws one or more kinds (the two targets share target.glsl): Gpu<Twin>,
// ds_<twin>_data, ds_<twin>_value, and DS_TEXTURE_COMPILED_<twin>, the specialization test that
// compiles it in. Texture.Constant has none: its value is GpuObject.shading.y.
#define DS_TEXTURE_MODELS(X)                                 \
  X(DS_TEXTURE_CONSTANT, Constant, constant)                 \
  X(DS_TEXTURE_FILE, File, file)                             \
  X(DS_TEXTURE_CHECKERBOARD, Checkerboard, target)           \
  X(DS_TEXTURE_CIRCLE_GRID, CircleGrid, target)              \
  X(DS_TEXTURE_SPECKLE, Speckle, speckle)

#define DS_LIGHT_POINT 0
#define DS_LIGHT_AMBIENT 1
#define DS_LIGHT_SPOT 2

#define DS_CAMERA_PINHOLE 0
#define DS_CAMERA_THIN_LENS 1      // pinhole chief ray + a lens disk sampled per sample (host/cameras/thin_lens.h)
#define DS_CAMERA_ORTHOGRAPHIC 2   // telecentric: rays parallel to the optical axis
#define DS_CAMERA_COUNT 3

// Camera kinds; a twin is the camera-frame ray of a kind other than the pinhole
// (ds_<file>_ray(GpuCamera, ...); with data of its own, Gpu<Type> and ds_<file>_data).
#define DS_CAMERA_MODELS(X)                                \
  X(DS_CAMERA_PINHOLE, Pinhole, pinhole)                   \
  X(DS_CAMERA_THIN_LENS, ThinLens, thin_lens)              \
  X(DS_CAMERA_ORTHOGRAPHIC, Orthographic, orthographic)

#define DS_DISTORTION_NONE 0
#define DS_DISTORTION_BROWN 1
#define DS_DISTORTION_RATIONAL 2  // OpenCV's full model: rational radial k1..k6, p1 p2, thin prism s1..s4

#ifdef __cplusplus
namespace dicsynth {
// The enumerators of the families with an X-list come from its rows: <Type> = DS_<FAMILY>_<NAME>.
#define DS_KIND_ENUMERATOR(KIND, Type, file) Type = KIND,
enum class ShapeKind : int { DS_ANALYTIC_SHAPES(DS_KIND_ENUMERATOR) Nurbs = DS_SHAPE_NURBS };
enum class ShaderKind : int { DS_REFLECTANCE_MODELS(DS_KIND_ENUMERATOR) };
enum class TextureKind : int { DS_TEXTURE_MODELS(DS_KIND_ENUMERATOR) };
enum class CameraKind : int { DS_CAMERA_MODELS(DS_KIND_ENUMERATOR) };
#undef DS_KIND_ENUMERATOR
enum class LightKind : int { Point = DS_LIGHT_POINT, Ambient = DS_LIGHT_AMBIENT, Spot = DS_LIGHT_SPOT };
enum class DistortionKind : int {
  None = DS_DISTORTION_NONE,
  Brown = DS_DISTORTION_BROWN,
  Rational = DS_DISTORTION_RATIONAL,
};
}  // namespace dicsynth
#endif

#endif
