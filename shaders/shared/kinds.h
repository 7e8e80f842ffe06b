// Closed lists of kinds, shared by C++ (host) and GLSL (shaders). Values are stored in GPU buffers:
// never renumber. An analytic shape kind has a home (host/shapes/<kind>.h, shaders/shapes/<kind>.glsl)
// and a row of DS_ANALYTIC_SHAPES below, from which CMakeLists.txt generates both registries'
// includes; a reflectance model (shader kind) has a home in host/reflectance/<kind>.h and, with a
// lobe, shaders/reflectance/; a texture in host/textures/ and shaders/textures/; a camera in
// host/cameras/ and shaders/cameras/ (docs/design.md §7).
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

// The analytic shape kinds (every kind but NURBS), one row each: X(number, C++ type, file), the
// file naming the home host/shapes/<file>.h (struct shapes::<type>) and its GLSL twin
// shaders/shapes/<file>.glsl (Gpu<Type>, ds_<file>_data, ds_<file>_search, ds_<file>_attributes).
// host/shapes/registry.h builds the variant shapes::Analytic from it, in this order, and
// shaders/lib/shapes.glsl its dispatch; CMakeLists.txt reads the rows (one per line, as written
// here) to generate the includes of the homes and twins. A new analytic kind is its number above,
// a row here, its home, its twin and its test (docs/design.md §7).
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

#define DS_TEXTURE_CONSTANT 0
#define DS_TEXTURE_FILE 1
#define DS_TEXTURE_CHECKERBOARD 2  // calibration targets, drawn analytically (texture/target_texture.h)
#define DS_TEXTURE_CIRCLE_GRID 3
#define DS_TEXTURE_SPECKLE 4  // analytic Boolean-model speckle in (u, v) (texture/analytic_speckle.h)
#define DS_TEXTURE_COUNT 5

#define DS_LIGHT_POINT 0
#define DS_LIGHT_AMBIENT 1
#define DS_LIGHT_SPOT 2

#define DS_CAMERA_PINHOLE 0
#define DS_CAMERA_THIN_LENS 1      // pinhole chief ray + a lens disk sampled per sample (host/cameras/thin_lens.h)
#define DS_CAMERA_ORTHOGRAPHIC 2   // telecentric: rays parallel to the optical axis
#define DS_CAMERA_COUNT 3

#define DS_DISTORTION_NONE 0
#define DS_DISTORTION_BROWN 1
#define DS_DISTORTION_RATIONAL 2  // OpenCV's full model: rational radial k1..k6, p1 p2, thin prism s1..s4

#ifdef __cplusplus
namespace dicsynth {
enum class ShapeKind : int {
  Sphere = DS_SHAPE_SPHERE,
  Box = DS_SHAPE_BOX,
  Triangle = DS_SHAPE_TRIANGLE,
  Plane = DS_SHAPE_PLANE,
  Rectangle = DS_SHAPE_RECTANGLE,
  Nurbs = DS_SHAPE_NURBS,
  Cylinder = DS_SHAPE_CYLINDER,
};
enum class ShaderKind : int {
  Constant = DS_SHADER_CONSTANT,
  Lambert = DS_SHADER_LAMBERT,
  Phong = DS_SHADER_PHONG,
  BlinnPhong = DS_SHADER_BLINN_PHONG,
  Ggx = DS_SHADER_GGX,
};
enum class TextureKind : int {
  Constant = DS_TEXTURE_CONSTANT,
  File = DS_TEXTURE_FILE,
  Checkerboard = DS_TEXTURE_CHECKERBOARD,
  CircleGrid = DS_TEXTURE_CIRCLE_GRID,
  Speckle = DS_TEXTURE_SPECKLE,
};
enum class LightKind : int { Point = DS_LIGHT_POINT, Ambient = DS_LIGHT_AMBIENT, Spot = DS_LIGHT_SPOT };
enum class CameraKind : int {
  Pinhole = DS_CAMERA_PINHOLE,
  ThinLens = DS_CAMERA_THIN_LENS,
  Orthographic = DS_CAMERA_ORTHOGRAPHIC,
};
enum class DistortionKind : int {
  None = DS_DISTORTION_NONE,
  Brown = DS_DISTORTION_BROWN,
  Rational = DS_DISTORTION_RATIONAL,
};
}  // namespace dicsynth
#endif

#endif
