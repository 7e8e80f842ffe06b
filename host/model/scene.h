#pragma once
// The scene as plain validated C++ structs in double precision: what a scene file describes.
// Produced by loadScene() (host/scene, the Lua layer above), consumed by prepareScene()
// (host/geometry) and the layers after it, which therefore include this file and not the Lua layer.
// Units: metres, radians, pixels where the name says _px. Frames: the camera frame is OpenCV's
// (x right, y down, z forward); world and object frames are right-handed.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/crc32.h"
#include "core/error.h"
#include "core/math.h"
#include "model/sensor_model.h"
#include "nurbs/nurbs_fit.h"
#include "nurbs/nurbs_surface.h"
#include "cameras/registry.h"
#include "reflectance/registry.h"
#include "shapes/registry.h"
#include "textures/registry.h"
#include "shared/kinds.h"

namespace dicsynth {

// OpenCV's lens distortion on normalized coordinates (docs/design.md §3, camera/distortion.h); maps
// ideal → distorted. Brown: k1 k2 k3 p1 p2. Rational: also k4 k5 k6 (radial denominator) and the
// thin-prism s1..s4.
struct Distortion {
  DistortionKind kind = DistortionKind::None;
  double k1 = 0, k2 = 0, k3 = 0;  // radial
  double p1 = 0, p2 = 0;          // tangential (OpenCV order; photogrammetry tools swap them)
  double k4 = 0, k5 = 0, k6 = 0;  // Rational: radial denominator
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;  // Rational: thin prism
};

struct Camera {
  std::string name;  // the scene's global variable name, e.g. "camera1"
  SourceLoc where;
  // The kind and its own parameters (host/cameras/<kind>.h); what follows, every kind shares.
  cameras::Model model;
  int width_px = 0, height_px = 0;
  dvec2 principalPoint_px{0, 0};  // OpenCV pixel frame: centre of the top-left pixel is (0, 0)
  dvec2 pixelSize_m{0, 0};
  double fillFactor = 1;   // area fraction of the pixel that is sensitive, (0, 1]
  int bitsPerPixel = 8;    // 1..16
  double exposure = 1;     // digital number = round(clamp(exposure * radiance, 0, 1) * (2^bits - 1))
  Distortion distortion;
  dmat4 worldFromCamera{1.0};  // rigid; identity = at the origin looking down +z, y down
  // The scene gave the pose (transform, position, lookAt or up). Rig.Stereo refuses such a camera:
  // the rig places its cameras, and silently dropping a pose the user wrote would hide a mistake.
  bool poseGiven = false;
  // Sensor model and post-processors (`sensor`, `postProcessing`; host/sensor). Empty: the plain
  // digitization above, exactly as without them.
  SensorModel sensor;

  CameraKind kind() const { return cameras::kindOf(model); }
  const cameras::CameraKindInfo& kindInfo() const { return cameras::cameraKindInfo(kind()); }
  // fx × pixel size: the lens-to-sensor distance (m) of a perspective camera, the magnification of a
  // telecentric one (cameras/<kind>.h).
  double focalScale() const {
    return std::visit([](const auto& k) { return k.focalScale(); }, model);
  }
};

// A shape in its own frame; `location` places that frame's origin in the object's frame.
// How a Nurbs.deform surface was made (scene/deform_constructors.cpp): the EXR header records it,
// the fieldError layer evaluates the requested field again at each pixel's material point.
struct Deformation {
  std::shared_ptr<const NurbsSurface> reference;  // S: the surface that was deformed (shape frame)
  DisplacementField field;  // d, callable after the scene ran (it keeps what it needs alive)
  std::string source;       // "Lua function (scene.lua:12)", or the mesh file, array and step
  std::optional<FileContent> meshFile;  // Field.load's file as read (a sweep point's asset)
  double tolerance_m = 0;
  NurbsFitReport report;
  bool fromCache = false;   // the fit of an earlier frame, verified against this frame's field
};
// One line for the EXR header: "field: ...; fit error E m (tolerance T m) on a U x V check grid;
// N control points; K refinements" (numbers with 17 significant digits).
std::string describeDeformation(const Deformation& deformation);

// A shape: one analytic kind with its parameters (host/shapes/<kind>.h), or a NURBS surface.
struct Shape {
  SourceLoc where;
  dvec3 location_m{0, 0, 0};  // the shape frame's origin in the object frame
  shapes::Analytic analytic;  // the shape unless `nurbs` is set
  std::shared_ptr<const NurbsSurface> nurbs;  // Shape.Nurbs: validated (validateNurbs), control
                                              // points relative to location
  std::shared_ptr<const Deformation> deformation;  // Nurbs.deform only: S, d and the fit's report
  ShapeKind kind() const { return nurbs ? ShapeKind::Nurbs : shapes::kindOf(analytic); }
};

struct Shader {
  SourceLoc where;
  dvec3 color{1, 1, 1};  // linear RGB; the renderer uses its luminance (grayscale sensor)
  reflectance::Model model;  // the kind and its own parameters (host/reflectance/<kind>.h)
  ShaderKind kind() const { return reflectance::kindOf(model); }
};

struct Texture {
  SourceLoc where;
  textures::Model model;  // the kind and its own parameters (host/textures/<kind>.h)
  TextureKind kind() const { return textures::kindOf(model); }
};

struct Object {
  std::string name;  // global variable name
  SourceLoc where;
  Shape shape;
  Shader shader;
  Texture texture;
  // Applied to the shape before `location`: worldFromShape = translate(location) * transform.
  // So a rotation turns the shape about its own location. Any invertible 4x4 homography.
  dmat4 transform{1.0};
};

struct Light {
  std::string name;
  SourceLoc where;
  LightKind kind = LightKind::Point;
  dvec3 position_m{0, 0, 0};
  // Point, Spot: radiant intensity (radiance units · m²); Ambient: incident radiance, the same
  // from every direction (radiance units). Luminance if given as RGB.
  double intensity = 1;
  dvec3 direction{0, 0, 1};  // Spot: unit axis of the cone (world)
  double innerAngle_rad = 0, outerAngle_rad = 0;  // Spot: full intensity within inner, none beyond outer
};

// Two cameras of the scene that form a stereo pair (Rig.Stereo). The rig's cameras are part of
// Scene::cameras under the names "<rig>.left" and "<rig>.right". Outputs state their relation as
// cv::stereoCalibrate does: x_right = R·x_left + T (camera frames, metres).
struct StereoRig {
  std::string name;   // the scene's global variable name
  SourceLoc where;
  std::string left, right;  // camera names
};

struct Scene {
  std::string file;               // the scene file as given
  std::vector<Camera> cameras;    // sorted by name
  std::vector<StereoRig> rigs;    // sorted by name
  std::vector<Object> objects;    // sorted by name; objectId = index + 1 (0 = background)
  std::vector<Light> lights;      // sorted by name
  // What the scene's values still need after loading: the Lua state of a scene whose Nurbs.deform
  // took a Lua function (the fieldError layer calls it again). Null for most scenes.
  std::shared_ptr<const void> keepAlive;
  // The -D defines (and sweep parameters) this evaluation did not read, in the order given; filled
  // only when SceneParams::requireDefinesRead is false (a run then checks them over its frames).
  std::vector<std::string> unreadDefines;
  // The globals this evaluation read while they were unset (nil: `strain = strain or 0.002`), sorted,
  // at most 256: what an unread define is likely a typo of ("did you mean 'strain'?").
  std::vector<std::string> unsetGlobalsRead;
  // CRC-32 of the scene file's bytes this evaluation ran: a run checks that every evaluation of its
  // frames (and a sweep, of its points) read one content (job/render_job.cpp).
  std::uint32_t sourceCrc32 = 0;
};

}  // namespace dicsynth
