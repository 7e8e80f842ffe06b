// Camera.<Kind> for every kind of host/cameras/registry.h (the parameters they share; each kind's own
// are its home's); Distortion.Brown, Distortion.Rational.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/warning.h"
#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "scene/sensor_constructors.h"

namespace dicsynth::scene {

namespace {

// The keys both distortion families share: `radial` (1..maxRadial of k1..k6; missing ones 0) and
// `tangential` {p1, p2}.
void readRadialTangential(const Params& p, Distortion& d, std::size_t maxRadial, const char* radialShape) {
  if (auto radial = p.numbers("radial", 1, maxRadial, radialShape)) {
    radial->resize(6, 0.0);
    d.k1 = (*radial)[0];
    d.k2 = (*radial)[1];
    d.k3 = (*radial)[2];
    d.k4 = (*radial)[3];
    d.k5 = (*radial)[4];
    d.k6 = (*radial)[5];
  }
  if (auto tangential = p.vec2("tangential", "{p1, p2}")) {
    d.p1 = tangential->x;
    d.p2 = tangential->y;
  }
}

/* ------------------------------------------------------------------------------------------------
Distortion.Brown: OpenCV's Brown–Conrady lens distortion on normalized coordinates
(x' = X/Z, y' = Y/Z, r² = x'² + y'²), mapping ideal → distorted:
  x'' = x'(1 + k1 r² + k2 r⁴ + k3 r⁶) + 2 p1 x'y' + p2 (r² + 2x'²)
  y'' = y'(1 + k1 r² + k2 r⁴ + k3 r⁶) + p1 (r² + 2y'²) + 2 p2 x'y'
Photogrammetry tools (Brown 1971, PhotoModeler, Metashape) swap p1 and p2 and work in mm:
convert before copying their values.

  Parameter   | Value                        | Default   | Meaning
  ------------+------------------------------+-----------+------------------------------------
  radial      | {k1[, k2[, k3]]} (unitless)  | {0, 0, 0} | radial coefficients; missing ones 0
  tangential  | {p1, p2} (unitless)          | {0, 0}    | tangential coefficients, exactly 2

Example:
  distortion = Distortion.Brown { radial = {-0.13, -0.39, 1.20}; tangential = {1.1e-6, -1.2e-6} }
------------------------------------------------------------------------------------------------ */
int distortionBrown(lua_State* L) {
  Params p(L, "Distortion.Brown", {"radial", "tangential"});
  Distortion distortion;
  distortion.kind = DistortionKind::Brown;
  readRadialTangential(p, distortion, 3, "{k1[, k2[, k3]]}");
  pushUserdata(L, distortion);
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Distortion.Rational: OpenCV's full lens model (cv::projectPoints with 8 or 12 coefficients,
CALIB_RATIONAL_MODEL | CALIB_THIN_PRISM_MODEL) on the camera's normalized coordinates:
  ρ = (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶)
  x'' = x' ρ + 2 p1 x'y' + p2 (r² + 2x'²) + s1 r² + s2 r⁴
  y'' = y' ρ + p1 (r² + 2y'²) + 2 p2 x'y' + s3 r² + s4 r⁴
OpenCV's vector is (k1, k2, p1, p2, k3, k4, k5, k6, s1, s2, s3, s4); the tilted-sensor terms
(τx, τy, 14 coefficients) are not offered.

  Parameter   | Value                              | Default      | Meaning
  ------------+------------------------------------+--------------+---------------------------------
  radial      | {k1[, ..., k6]} (unitless)         | all 0        | k1..k3 numerator, k4..k6
              |                                    |              | denominator; missing ones 0
  tangential  | {p1, p2} (unitless)                | {0, 0}       | tangential, exactly 2
  thinPrism   | {s1, s2, s3, s4} (unitless)        | {0, 0, 0, 0} | thin prism, exactly 4

The denominator must stay positive over the image (checked where the distortion is inverted).
Example:
  distortion = Distortion.Rational { radial = {0.1, -0.05, 0, 0.08, -0.02, 0.001};
                                     thinPrism = {1e-3, 0, -5e-4, 0} }
------------------------------------------------------------------------------------------------ */
int distortionRational(lua_State* L) {
  Params p(L, "Distortion.Rational", {"radial", "tangential", "thinPrism"});
  Distortion d;
  d.kind = DistortionKind::Rational;
  readRadialTangential(p, d, 6, "{k1[, k2[, ..., k6]]}");
  if (auto prism = p.numbers("thinPrism", 4, 4, "{s1, s2, s3, s4}")) {
    d.s1 = (*prism)[0];
    d.s2 = (*prism)[1];
    d.s3 = (*prism)[2];
    d.s4 = (*prism)[3];
  }
  pushUserdata(L, d);
  return 1;
}

// Checks that worldFromCamera is rigid: orthonormal rotation (to 1e-9), det +1, last row 0 0 0 1.
dmat4 checkRigid(const Params& p, const dmat4& m) {
  const char* what = "'transform' (worldFromCamera) must be rigid, a rotation and a translation";
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(m[col][row])) p.fail(std::string(what) + ", but it is not finite");
  const double bottom = std::max(
      {std::fabs(m[0][3]), std::fabs(m[1][3]), std::fabs(m[2][3]), std::fabs(m[3][3] - 1.0)});
  if (bottom > 1e-9) p.fail(std::string(what) + ", but its bottom row is not 0 0 0 1");
  const dmat3 rotation(m);
  const dmat3 gram = glm::transpose(rotation) * rotation;
  double deviation = 0;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row)
      deviation = std::max(deviation, std::fabs(gram[col][row] - (col == row ? 1.0 : 0.0)));
  if (deviation > 1e-9)
    p.fail(std::string(what) + ", but its 3x3 part is not orthonormal (max |R^T R - I| = " +
           formatNumber(deviation) + ")");
  if (glm::determinant(rotation) < 0)
    p.fail(std::string(what) + ", but it mirrors (determinant -1)");
  dmat4 rigid = m;
  rigid[0][3] = rigid[1][3] = rigid[2][3] = 0;
  rigid[3][3] = 1;
  return rigid;
}

// worldFromCamera from position, lookAt and up (OpenCV camera frame: x right, y down, z forward).
dmat4 lookAtPose(const Params& p, const dvec3& position, const dvec3& lookAt, const dvec3& up) {
  const dvec3 forward = lookAt - position;
  const double distance = glm::length(forward);
  if (distance <= 1e-12 * std::max({1.0, glm::length(position), glm::length(lookAt)}))
    p.fail("'lookAt' must differ from 'position'");
  const dvec3 z = forward / distance;
  // The image's y axis points down, i.e. against the part of `up` across the viewing direction.
  const dvec3 upAcross = up - glm::dot(up, z) * z;
  // The values in the message: a camera made in a loop names no variable (the 360° trial of
  // 2026-11-29 could not tell which of six cameras it was), and `up` may be the default.
  if (!(glm::length(upAcross) > 1e-9 * glm::length(up))) {
    const auto text = [](dvec3 v) {
      return "{" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + "}";
    };
    p.fail("'up' must not be zero or parallel to the viewing direction (lookAt - position): up = " + text(up) +
           (p.has("up") ? "" : " (the default)") + ", position = " + text(position) + ", lookAt = " + text(lookAt));
  }
  const dvec3 y = glm::normalize(-upAcross);
  const dvec3 x = glm::cross(y, z);
  return dmat4(dvec4(x, 0), dvec4(y, 0), dvec4(z, 0), dvec4(position, 1));
}

/* ------------------------------------------------------------------------------------------------
Camera.<Kind> (every kind: Camera.Pinhole, Camera.ThinLens, Camera.Orthographic): a camera with a
rectangular sensor of square-grid pixels. Pixel coordinates are OpenCV's: the centre of the
top-left pixel is (0, 0), x right, y down. The camera frame is OpenCV's: x right, y down, z forward
(along the optical axis). Every kind reads the parameters of this table (kCommonCameraKeys,
readCommonCamera below) and its own (host/cameras/<kind>.h: focalLength, magnification, ...).

  Parameter      | Value                  | Default            | Meaning
  ---------------+------------------------+--------------------+----------------------------------
  resolution     | {w, h} integers, px    | required           | image size, each 1..65535
  principalPoint | {cx, cy}, px           | {(w-1)/2, (h-1)/2} | where the optical axis meets the
                 |                        |                    | image (default: geometric centre)
  pixelSize      | {sx, sy}, m            | required           | pixel pitch, each > 0, sx / sy
                 |                        |                    | in 1e-3..1e3
  fillFactor     | number                 | 1                  | sensitive fraction of a pixel's
                 |                        |                    | area, in (0, 1]
  bitsPerPixel   | integer                | 8                  | 1..16
  exposure       | number                 | 1                  | > 0; DN = round(clamp(exposure *
                 |                        |                    | radiance, 0, 1) * (2^bits - 1))
  distortion     | Distortion             | none               | Distortion.Brown or .Rational
  sensor         | Sensor                 | none (ideal)       | Sensor.Emva { ... } (docs/sensor.md)
  postProcessing | {PostProcessor, ...}   | none               | Blur, Vignetting, Dust, Defective-
                 |                        |                    | Pixels (docs/sensor.md)
  transform      | Transform              | identity           | pose as worldFromCamera; must be
                 |                        |                    | rigid (rotation + translation)
  position       | {x, y, z}, m           | {0, 0, 0}          | camera centre (optical centre)
  lookAt         | {x, y, z}, m           | -                  | a point on the optical axis
  up             | {x, y, z}              | {0, -1, 0}         | world direction shown up in the
                 |                        |                    | image; only with lookAt

Pose: give `transform`, or `position` with optional `lookAt`/`up`, not both. Without any, the
camera sits at the origin looking down +z and its frame is the world frame. With lookAt:
  z = normalize(lookAt - position), y = normalize(-(up - (up · z) z)), x = cross(y, z).
Without lookAt the camera at `position` keeps the world's orientation.
------------------------------------------------------------------------------------------------ */

// A length far outside what cameras have is nearly always another unit typed as metres: a 16 mm lens
// as focalLength = 16 framed 0.02 degrees of the plate, pixelSize = {5, 5} (um) 180 degrees, both
// rendered without a word (the docs walk and the optics trial of 2026-11-29). Said, not refused:
// the renderer renders such a camera as asked. Real lenses: ~1 mm (phones, endoscopes) to ~1 m
// (telephoto); real pixels: ~0.5 to ~30 um; the bounds leave a decade on each side. Once per line.
// `perMetre` and `unit` name the unit the value was probably meant in (1e3, "mm").
bool warnImplausibleLength(const SourceLoc& where, const char* key, double value_m, double lo_m, double hi_m,
                           double perMetre, const char* unit) {
  if (value_m >= lo_m && value_m <= hi_m) return false;
  const std::string text = where.str() + ": " + key + " = " + formatNumber(value_m) + " m is outside " + formatNumber(lo_m) +
                           " .. " + formatNumber(hi_m) + " m, where cameras have it: lengths are metres (" +
                           formatNumber(value_m / perMetre) + " m for " + formatNumber(value_m) + " " + unit + ")";
  // Once per line and key, whatever the value (a focal length changing with the frame said it for
  // every frame: the review of 2026-11-29).
  warnAtMost("implausible camera length: " + where.str() + " " + key, 1, text);
  return true;
}

// The keys every Camera.* constructor reads through readCommonCamera.
const std::vector<const char*> kCommonCameraKeys = {
    "resolution", "principalPoint", "pixelSize", "fillFactor", "bitsPerPixel", "exposure",
    "distortion", "transform", "position", "lookAt", "up", "sensor", "postProcessing"};

// Sensor, distortion and pose: the parameters every camera kind shares (table above).
// `kind`: the kind's defaults until its own parameters are read (the sensor's checks ask its properties).
Camera readCommonCamera(lua_State* L, const Params& p, const cameras::Model& kind) {
  Camera camera;
  camera.model = kind;
  camera.where = LuaSandbox::of(L).here(L);

  // Sensor
  auto resolution = p.vec2("resolution", "{width, height}");
  if (!resolution) p.fail("missing required 'resolution' = {width, height}");
  for (double n : {resolution->x, resolution->y})
    p.require(n == std::floor(n) && n >= 1 && n <= 65535, "resolution", "two integers in 1..65535",
              n);
  camera.width_px = static_cast<int>(resolution->x);
  camera.height_px = static_cast<int>(resolution->y);
  camera.principalPoint_px = p.vec2("principalPoint", "{cx, cy}")
                                 .value_or(dvec2(camera.width_px - 1, camera.height_px - 1) / 2.0);
  auto pixelSize = p.vec2("pixelSize", "{sx, sy}");
  if (!pixelSize) p.fail("missing required 'pixelSize' = {sx, sy} (metres)");
  for (double s : {pixelSize->x, pixelSize->y})
    p.require(s > 0, "pixelSize", "> 0 (metres) in x and y", s);
  // No sensor has pixels a thousand times longer than wide; OpenEXR refuses aspects beyond 1e6.
  const double aspect = pixelSize->x / pixelSize->y;
  if (!(aspect >= 1e-3 && aspect <= 1e3))
    p.fail("'pixelSize' = {" + formatNumber(pixelSize->x) + ", " + formatNumber(pixelSize->y) +
           "}: the pixel aspect sx / sy = " + formatNumber(aspect) + " must be in 1e-3..1e3");
  camera.pixelSize_m = *pixelSize;
  for (const double size_m : {pixelSize->x, pixelSize->y})
    if (warnImplausibleLength(camera.where, "pixelSize", size_m, 1e-7, 1e-3, 1e6, "um")) break;
  camera.fillFactor = p.number("fillFactor", 1.0);
  p.require(camera.fillFactor > 0 && camera.fillFactor <= 1, "fillFactor", "in (0, 1]",
            camera.fillFactor);
  const long long bits = p.integer("bitsPerPixel").value_or(8);
  p.require(bits >= 1 && bits <= 16, "bitsPerPixel", "an integer in 1..16",
            static_cast<double>(bits));
  camera.bitsPerPixel = static_cast<int>(bits);
  camera.exposure = p.number("exposure", 1.0);
  p.require(camera.exposure > 0, "exposure", "> 0", camera.exposure);
  if (const Distortion* distortion =
          p.userdata<Distortion>("distortion", "a Distortion (Distortion.Brown, Distortion.Rational)"))
    camera.distortion = *distortion;
  readCameraSensor(L, p, camera);  // sensor, postProcessing (sensor_constructors.cpp)

  // Pose
  const TransformValue* transform =
      p.userdata<TransformValue>("transform", "a Transform (translate, rotate_x, ..., homography)");
  const bool byPosition = p.has("position") || p.has("lookAt") || p.has("up");
  if (transform && byPosition)
    p.fail("give either 'transform' or 'position'/'lookAt'/'up', not both");
  camera.poseGiven = transform != nullptr || byPosition;
  if (transform) {
    camera.worldFromCamera = checkRigid(p, transform->matrix);
  } else if (byPosition) {
    const dvec3 position = p.vec3("position").value_or(dvec3(0));
    const std::optional<dvec3> lookAt = p.vec3("lookAt");
    const std::optional<dvec3> up = p.vec3("up");
    if (up && !lookAt) p.fail("'up' needs 'lookAt' (it orients the viewing direction)");
    camera.worldFromCamera = lookAt ? lookAtPose(p, position, *lookAt, up.value_or(dvec3(0, -1, 0)))
                                    : glm::translate(dmat4(1.0), position);
  }
  return camera;
}

// Camera.<Kind>: the common parameters, then the kind's own (its home parses them).
template <class Kind>
int cameraConstructor(lua_State* L) {
  std::vector<const char*> keys = kCommonCameraKeys;
  keys.insert(keys.end(), Kind::kKeys.begin(), Kind::kKeys.end());
  Params p(L, std::string("Camera.") + Kind::kName, keys);
  Camera camera = readCommonCamera(L, p, Kind{});
  const Kind kind = Kind::parse(p);
  if constexpr (requires { kind.focalLength_m; }) warnImplausibleLength(camera.where, "focalLength", kind.focalLength_m, 1e-4, 2, 1e3, "mm");
  camera.model = kind;
  pushUserdata(L, std::move(camera));
  return 1;
}

int cameraToString(lua_State* L) {
  const Camera* camera = toUserdata<Camera>(L, 1);
  const char* kind = camera ? camera->kindInfo().name : cameras::Pinhole::kName;
  lua_pushfstring(L, "Camera.%s(%dx%d)", kind, camera ? camera->width_px : 0, camera ? camera->height_px : 0);
  return 1;
}

int distortionToString(lua_State* L) {
  const Distortion* d = toUserdata<Distortion>(L, 1);
  if (d && d->kind == DistortionKind::Rational) lua_pushliteral(L, "Distortion.Rational");
  else lua_pushliteral(L, "Distortion.Brown");
  return 1;
}

}  // namespace

void registerCameraConstructors(lua_State* L) {
  registerUserdataType<Camera>(L, {{"__tostring", &cameraToString}});
  registerUserdataType<Distortion>(L, {{"__tostring", &distortionToString}});
  std::vector<luaL_Reg> kinds;
  cameras::forEachCameraKind([&](auto kind) {
    using K = typename decltype(kind)::type;
    kinds.push_back({K::kName, &protectedCall<cameraConstructor<K>>});
  });
  setConstructorTable(L, "Camera", kinds);
  setConstructorTable(L, "Distortion", {{"Brown", &protectedCall<distortionBrown>},
                                         {"Rational", &protectedCall<distortionRational>}});
}

}  // namespace dicsynth::scene
