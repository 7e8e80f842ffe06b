#pragma once
// PreparedScene: a Scene made ready for rendering, consumed identically by the CPU reference
// (host/cpu) and the GPU backend (host/gpu/pack.cpp). Everything is double; the GPU packs it down
// to its precision variant.
#include <compare>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cameras/rays.h"
#include "core/crc32.h"
#include "core/file_stamp.h"
#include "geometry/nurbs_bvh.h"
#include "geometry/object_map.h"
#include "geometry/shapes.h"
#include "geometry/targets.h"
#include "model/scene.h"
#include "texture/analytic_speckle.h"
#include "texture/bspline.h"

namespace dicsynth {

class TextureCache;  // geometry/texture_cache.h

struct PreparedCamera {
  Camera camera;               // the scene's camera (after --downscale)
  PinholeModel<double> model;  // intrinsics in px, distortion, pose
  dmat3 rotationCameraFromWorld;     // OpenCV R:  x_cam = R x_world + t
  dvec3 translationCameraFromWorld;  // OpenCV t
};

struct PreparedObject {
  std::string name;
  std::uint32_t id = 0;  // objectId in the outputs (index + 1)
  ShapeGeometry geometry;  // for a NURBS shape, geometry.nurbs == nurbs.get()
  std::shared_ptr<const PreparedNurbs> nurbs;  // Bézier patches, sub-patches, BVH (Nurbs only)
  std::shared_ptr<const NurbsSurface> surface; // the scene's surface (Nurbs only; scene shape frame)
  std::shared_ptr<const Deformation> deformation;  // Nurbs.deform only: S, d, the fit (scene.h)
  reflectance::Model shader;  // the reflectance model and its parameters (host/reflectance)
  double albedo = 1;          // luminance of the shader colour
  // The texture and its parameters (host/textures), prepared: a File's image (shared with
  // PreparedScene::textures[index]), a target's drawing in (u, v).
  textures::Model texture;
  // A calibration target's layout and features (geometry/targets.h); null for other objects.
  std::shared_ptr<const TargetLayout> target;
  dmat4 worldFromTarget{1.0};   // the target frame in the world (targets only; rigid)
  dmat4 worldFromObject{1.0}; // translate(location) * transform * translate(shapeOffset_m)
  // Where the prepared shape's origin lies in the scene shape's frame: (0, 0, 0), except for a
  // NURBS, whose control points are re-centred (prepare.cpp). A point p of the scene's shape frame
  // is worldFromObject · (p − shapeOffset_m).
  dvec3 shapeOffset_m{0};
  ObjectFromWorld objectFromWorld;  // worldFromObject's inverse, relative to the object's origin
};

struct PreparedLight {
  LightKind kind = LightKind::Point;
  dvec3 position_m{0};
  double intensity = 1;      // Point, Spot: intensity; Ambient: incident radiance
  dvec3 direction{0, 0, 1};  // Spot: unit axis
  double cosOuter = -1, cosInner = -1;  // Spot: cosines of the outer and inner half-angles
};

struct PreparedTexture {
  std::string path;
  int width = 0, height = 0;
  Interpolation interpolation = Interpolation::Cubic;
  TextureWrap wrap = TextureWrap::Clamp;
  // B-spline coefficients for that kernel and those borders (texture/bspline.h), row-major. Shared and immutable: the
  // texture cache, every point of a sweep and the GPU's uploaded copy (gpu/renderer.cpp) refer to
  // the same array (Figure 1's texture is 67 MB of doubles), so a point neither copies nor repacks it.
  std::shared_ptr<const std::vector<double>> coefficients = std::make_shared<const std::vector<double>>();
  const std::vector<double>& values() const { return *coefficients; }
  // The file's stamp (core/file_stamp.h) when it was read, the same before and after the reading:
  // the content these coefficients come from. Caches key by it.
  FileStamp stamp;
  // The CRC-32 (core/crc32.h) of the file's bytes under that stamp: what a sweep's point records as
  // the texture it rendered, and what tells a file touched or copied over with the same bytes (its
  // stamp moves) from one with another content.
  std::uint32_t contentCrc32 = 0;
  // Whether the file at `path` still holds the content these coefficients were prepared from: its
  // stamp unchanged, or its bytes' CRC-32 unchanged. False when it cannot be read.
  bool fileUnchanged() const;
};

// Features the scene uses; the GPU switches the others off with specialization constants.
struct SceneFeatures {
  bool lights = false;        // some lit (non-Constant) object and at least one light: shading loop + shadow rays
  bool distortion = false;    // some camera has lens distortion: Newton inversion per ray
  bool fileTextures = false;  // some object has a Texture.File: B-spline lookups
  std::uint32_t shapeKinds = 0;  // bit k set: some object has shape kind k (DS_SHAPE_*)
  int nurbsDegree = 0;           // highest degree of any NURBS patch (GPU raises all to it), 0: none
  bool speckleTextures = false;  // some object has a Texture.Speckle: analytic disk tests
  bool quinticTextures = false;  // some Texture.File uses quintic interpolation: 6×6 lookups
  bool targetTextures = false;   // some object has a calibration target (Checkerboard, CircleGrid)
  // Bit k set: some camera has kind k (DS_CAMERA_*). The pinhole is the GPU's default branch, so
  // only the other bits switch code on.
  std::uint32_t cameraKinds = 0;
  bool rationalDistortion = false;  // some camera has Distortion.Rational: k4..k6, s1..s4 terms
  std::uint32_t shaderKinds = 0;  // bit k set: some object has shader kind k (DS_SHADER_*)
  std::uint32_t lightKinds = 0;   // bit k set: some light has kind k (DS_LIGHT_*), 0 without lights

  bool hasShape(ShapeKind kind) const { return (shapeKinds & (1u << int(kind))) != 0; }

  static SceneFeatures all(int nurbsDegree) {
    return {true, true, true, ~0u, nurbsDegree, true, true, true, ~0u, true, ~0u, ~0u};
  }
  auto operator<=>(const SceneFeatures&) const = default;
};

struct PreparedRig {
  std::string name;
  int left = -1, right = -1;  // indices into PreparedScene::cameras
};

struct PreparedScene {
  std::string file;
  std::vector<PreparedCamera> cameras;
  std::vector<PreparedRig> rigs;
  std::vector<PreparedObject> objects;
  std::vector<PreparedLight> lights;
  std::vector<PreparedTexture> textures;
  SceneFeatures features;
  // Scene::keepAlive: what objects' deformations call after the scene's own lifetime (fieldError).
  std::shared_ptr<const void> keepAlive;
};

// The pinhole model (intrinsics in px, distortion, pose) of a scene camera, as rendered.
PinholeModel<double> pinholeModel(const Camera& camera);

struct PrepareOptions {
  // Integer factor dividing the resolution while keeping the field of view: pixel size × k,
  // principal point c' = (c + 1/2)/k − 1/2 (OpenCV pixel centres). For previews and fast tests.
  int downscale = 1;
  // Optional (geometry/texture_cache.h): file textures prepared by earlier calls are reused.
  TextureCache* textureCache = nullptr;
  // false: file textures are named, not read (PreparedTexture with its path and interpolation, no
  // size, no coefficients): the scene's features and counts, which a GPU pipeline's key needs,
  // before the textures are read (job/render_job.cpp, renderFrame). Such a scene is never rendered.
  bool textureData = true;
};

// The camera a stereo rig pairs with camera `camera` (an index into scene.cameras): the one whose
// view `disparity` measures. -1 when the camera is in no rig.
inline int rigPartner(const PreparedScene& scene, std::size_t camera) {
  for (const PreparedRig& rig : scene.rigs) {
    if (rig.left == int(camera)) return rig.right;
    if (rig.right == int(camera)) return rig.left;
  }
  return -1;
}

// Throws InputError (with the scene's file:line) for what only shows up now: unreadable textures,
// distortion that cannot be inverted over the image, a camera or light on an object's plane at
// infinity, a calibration target wholly behind a camera (none of its features in front of it).
PreparedScene prepareScene(const Scene& scene, const PrepareOptions& options = {});

// Calls `visit(kind, file)` for each file the prepared scene read besides the scene file, as it
// read it: every texture ("texture") and every Field.load mesh ("mesh"). What a sweep point
// records as its assets and what every frame of a run must read alike (job/render_job.cpp).
void forEachInputFile(const PreparedScene& scene,
                      const std::function<void(const char* kind, const FileContent& file)>& visit);

}  // namespace dicsynth
