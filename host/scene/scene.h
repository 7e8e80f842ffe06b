#pragma once
// Scene: what a scene file describes, as plain validated C++ structs in double precision.
// Produced by loadScene() (host/scene/lua_scene.cpp), consumed by prepareScene() (host/geometry).
// Units: metres, radians, pixels where the name says _px. Frames: the camera frame is OpenCV's
// (x right, y down, z forward); world and object frames are right-handed.
#include <array>
#include <memory>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "geometry/nurbs_fit.h"
#include "geometry/nurbs_surface.h"
#include "sensor/sensor_model.h"
#include "shared/kinds.h"
#include "texture/analytic_speckle.h"
#include "texture/bspline.h"

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
  CameraKind kind = CameraKind::Pinhole;
  int width_px = 0, height_px = 0;
  dvec2 principalPoint_px{0, 0};  // OpenCV pixel frame: centre of the top-left pixel is (0, 0)
  double focalLength_m = 0;   // Pinhole: pinhole distance; ThinLens: the lens's focal length f
  dvec2 pixelSize_m{0, 0};
  double aperture_m = 0;       // ThinLens: aperture diameter A (from `aperture` or f/`fNumber`)
  double focusDistance_m = 0;  // ThinLens: object distance u in focus, along the axis from the lens
  double magnification = 0;    // Orthographic: image size / object size
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
};

// A shape in its own frame; `location` places that frame's origin in the object's frame.
// Per-kind parameters (others unused):
//   Sphere:    radius_m
//   Box:       size_m (full edge lengths x, y, z)
//   Rectangle: size_m.x, size_m.y (in the local xy-plane)
//   Plane:     size_m.x, size_m.y = texture tile size (u, v repeat every tile)
//   Triangle:  vertices_m[3] (relative to location), vertexUV[3]
//   Nurbs:     nurbs (control points relative to location)
// How a Nurbs.deform surface was made (scene/deform_constructors.cpp): the EXR header records it,
// the fieldError layer evaluates the requested field again at each pixel's material point.
struct Deformation {
  std::shared_ptr<const NurbsSurface> reference;  // S: the surface that was deformed (shape frame)
  DisplacementField field;  // d, callable after the scene ran (it keeps what it needs alive)
  std::string source;       // "Lua function (scene.lua:12)", or the mesh file, array and step
  double tolerance_m = 0;
  NurbsFitReport report;
  bool fromCache = false;   // the fit of an earlier frame, verified against this frame's field
};
// One line for the EXR header: "field: ...; fit error E m (tolerance T m) on a U x V check grid;
// N control points; K refinements" (numbers with 17 significant digits).
std::string describeDeformation(const Deformation& deformation);

struct Shape {
  ShapeKind kind = ShapeKind::Sphere;
  SourceLoc where;
  dvec3 location_m{0, 0, 0};
  double radius_m = 0;
  dvec3 size_m{0, 0, 0};
  std::array<dvec3, 3> vertices_m{};
  std::array<dvec2, 3> vertexUV{dvec2{0, 0}, dvec2{1, 0}, dvec2{0, 1}};
  std::shared_ptr<const NurbsSurface> nurbs;  // validated (validateNurbs)
  std::shared_ptr<const Deformation> deformation;  // Nurbs.deform only: S, d and the fit's report
};

struct Shader {
  ShaderKind kind = ShaderKind::Constant;
  SourceLoc where;
  dvec3 color{1, 1, 1};  // linear RGB; the renderer uses its luminance (grayscale sensor)
  // Specular parameters (host/cpu/shading.h has the formulas; shading_constructors.cpp the docs).
  double specular = 0;   // Phong, BlinnPhong: ks, the specular lobe's weight
  int shininess = 1;     // Phong, BlinnPhong: exponent n (an integer, shading.h says why)
  double roughness = 0;  // GGX: α (Trowbridge-Reitz width; α = perceptual roughness²)
  double f0 = 0;         // GGX: Fresnel reflectance at normal incidence (Schlick)
};

// The printed pattern of a calibration target (Target.Checkerboard, Target.CircleGrid); its layout,
// the target frame and its features are defined in host/geometry/targets.h.
struct TargetPattern {
  int cols = 0, rows = 0;   // Checkerboard: squares per row, rows of squares. CircleGrid: circles
                            // per row, rows (OpenCV's patternSize)
  bool asymmetric = false;  // CircleGrid: OpenCV's CALIB_CB_ASYMMETRIC_GRID layout
  double spacing_m = 0;     // Checkerboard: square size. CircleGrid: OpenCV's squareSize (row
                            // pitch; centres in a row are 2·spacing apart when asymmetric)
  double radius_m = 0;      // CircleGrid: dot radius
  double border_m = 0;      // light margin around the squares / around the dots' edges
  double dark = 0, light = 1;  // texture values of the dark and the light parts
};

struct Texture {
  TextureKind kind = TextureKind::Constant;
  SourceLoc where;
  double value = 1;      // Constant
  std::string path;      // File: resolved path (relative paths resolve against the scene's folder)
  TargetPattern target;  // Checkerboard, CircleGrid
  Interpolation interpolation = Interpolation::Cubic;  // File
  AnalyticSpeckle speckle;  // Speckle (texture/analytic_speckle.h)
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
};

// Values set as Lua globals before the scene runs.
struct SceneParams {
  std::vector<std::pair<std::string, std::string>> defines;  // -D name=value (number/bool/string)
  int frame = 0;                                              // global `frame`
  // Names among `defines` set by a sweep point (dicsynth sweep): messages call them sweep
  // parameters instead of -D options.
  std::vector<std::string> sweepParameters;
  // Limits of the scene's Lua code. A real scene runs in milliseconds and needs a few MiB; the
  // limits only turn a runaway scene (endless loop, table growing without end) into a clear
  // "FILE:LINE: scene exceeded the ... limit" error instead of a hang or an exhausted machine.
  // Instructions: Lua VM instructions; this machine runs ~200 M/s, so the default stops a
  // runaway loop within about half a second, yet leaves ~20x the headroom that a scene building
  // 100 000 triangles in a loop (~5 M instructions) needs.
  std::uint64_t maxInstructions = 100'000'000;
  // Memory: bytes of the Lua heap. A scene value is under 1 KiB, so 256 MiB holds well over
  // 100 000 objects; far beyond what the renderers take, far below the machine's memory.
  std::size_t maxMemoryBytes = std::size_t{256} << 20;
  // Wall-clock time of the evaluation (seconds). Real scenes take milliseconds, Nurbs.deform fits
  // up to a few seconds (bench/RESULTS.md); a minute stops a runaway scene whose loop of long
  // calls the instruction limit cannot see. 0: the environment's DICSYNTH_SCENE_SECONDS, else 60.
  double maxSeconds = 0;
  // The scene's print and constructors' reports (Nurbs.deform's fit) write nothing: set when a
  // scene is evaluated again after a first evaluation whose output the user saw (render, sweep).
  bool quiet = false;
};

// The longest camera name (with a rig's ".left"/".right"): names become output file names.
inline constexpr std::size_t kMaxCameraNameBytes = 128;

// The largest scene file loadScene reads (README, "Limits").
inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t(16) << 20;

// Whether `name` is taken by the scene language (a constructor table, a function, a Lua library,
// a keyword, `frame`): a -D option or a sweep parameter cannot use it.
bool isSceneLanguageName(const std::string& name);

// Loads and validates a scene. Throws InputError("file:line: message") on any error.
Scene loadScene(const std::string& path, const SceneParams& params);

}  // namespace dicsynth
