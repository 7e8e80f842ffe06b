#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include "core/crc32.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/math.h"
#include "core/option_names.h"
#include "core/parallel.h"
#include "files/file_bytes.h"
#include "files/image_io.h"
#include "geometry/homography.h"
#include "geometry/prepared_scene.h"
#include "geometry/targets.h"
#include "geometry/texture_cache.h"
#include "texture/bspline.h"

namespace dicsynth {
namespace {

Camera downscaled(Camera c, int k) {
  if (k == 1) return c;
  if (c.width_px / k < 1 || c.height_px / k < 1)
    throw InputError(c.where, optionName("--downscale") + " " + std::to_string(k) + " leaves camera '" + c.name +
                                  "' without pixels (" + std::to_string(c.width_px) + "x" +
                                  std::to_string(c.height_px) + ")");
  c.width_px /= k;
  c.height_px /= k;
  c.pixelSize_m *= double(k);
  // A new pixel covers k×k old ones; its centre (i + 1/2)k − 1/2 in old pixel coordinates.
  c.principalPoint_px = (c.principalPoint_px + 0.5) / double(k) - 0.5;
  c.sensor.downscale = k;  // its pixel lengths and positions are converted where it is applied
  return c;
}

// The sensitive area of the image reaches half a pixel beyond the outermost pixel centres. Every
// sample position there must invert to the ideal point a lens images there: the root joined to the
// image centre (camera/distortion.h, undistortContinued), round-tripping to far below 1e-9 px. The
// renderer's inversion, Newton from the distorted point (the samples' on the GPU from their pixel
// centre's root), must land on that root: Newton can converge to another one, beyond a fold or on
// the branch where ρ < 0 (det J > 0 there too), and that pixel would then see along a wrong ray
// without a word (Newton from the target reached another root on 150 of 40,000 random targets of
// random radial models, tests/camera/test_distortion_inverse_path.cpp). Checked on the border and on an 8 px grid inside; a model refused here is either folded
// between the centre and the image's edge or has a second root that Newton reaches from the image.
// Each camera model is checked once per process (the frames of a run usually share it).
void checkDistortionInvertible(const PreparedCamera& pc) {
  const auto& m = pc.model;
  if (!m.distorted) return;
  const double w = pc.camera.width_px, h = pc.camera.height_px;
  using Key = std::array<double, 18>;
  const Key key{m.brown.k1, m.brown.k2, m.brown.k3, m.brown.p1, m.brown.p2, m.brown.k4, m.brown.k5, m.brown.k6,
                m.brown.s1, m.brown.s2, m.brown.s3, m.brown.s4, m.fx, m.fy, m.cx, m.cy, w, h};
  static std::mutex mutex;
  static std::vector<Key> accepted;  // the last kRemembered models that passed
  constexpr std::size_t kRemembered = 16;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (std::find(accepted.begin(), accepted.end(), key) != accepted.end()) return;
  }
  // Why the inversion fails at `target`, or "" where it does not.
  auto failure = [&m](dvec2 target) -> std::string {
    dvec2 principal, newton;
    if (!undistortContinued(m.brown, target, principal))
      return "between the image centre and there the distortion folds over or reaches a pole of its denominator";
    // Two roots agree to the stopping step's rounding (1e-14 normalized, ~1e-11 px): 1e-9 px apart
    // is another root.
    const bool newtonConverged = undistortNewton(m.brown, target, target, newton);
    if (newtonConverged &&
        std::max(std::abs(newton.x - principal.x) * m.fx, std::abs(newton.y - principal.y) * m.fy) > 1e-9) {
      std::ostringstream why;
      why << "besides the ideal point joined to the image centre, (" << principal.x << ", " << principal.y
          << "), the point (" << newton.x << ", " << newton.y
          << ") beyond a fold maps there too, and the inversion from the image reaches it";
      return why.str();
    }
    // undistort()'s answer, from the two roots at hand: Newton's where it converged, else the path's.
    const dvec2 back = distort(m.brown, newtonConverged ? newton : principal);
    const double err_px = std::max(std::abs(back.x - target.x) * m.fx, std::abs(back.y - target.y) * m.fy);
    return err_px < 1e-9 ? "" : "the inverse does not round-trip to 1e-9 px";
  };
  std::vector<dvec2> points;  // image positions (px): the border, then the grid
  for (double x = -0.5; x <= w - 0.5; x += 1) points.insert(points.end(), {{x, -0.5}, {x, h - 0.5}});
  for (double y = -0.5; y <= h - 0.5; y += 1) points.insert(points.end(), {{-0.5, y}, {w - 0.5, y}});
  for (double y = 0; y < h; y += 8)
    for (double x = 0; x < w; x += 8) points.push_back({x, y});
  // On all cores (Figure 1's camera, 1600 x 1200: 35,000 points; its prepare took 0.068 s against
  // 0.034 s without distortion on 2 cores, medians of 5 interleaved runs, 2026-11-28); the first
  // point that fails in the order above is the one named, whichever thread finds it.
  constexpr std::size_t kBlock = 512;
  std::vector<std::size_t> firstFailed((points.size() + kBlock - 1) / kBlock, points.size());
  std::vector<std::string> why(firstFailed.size());
  parallelForBlocks(points.size(), kBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      std::string text = failure({(points[i].x - m.cx) / m.fx, (points[i].y - m.cy) / m.fy});
      if (text.empty()) continue;
      firstFailed[begin / kBlock] = i;
      why[begin / kBlock] = std::move(text);
      return;
    }
  });
  for (std::size_t b = 0; b < firstFailed.size(); ++b) {
    if (firstFailed[b] == points.size()) continue;
    std::ostringstream msg;
    msg << (pc.camera.distortion.kind == DistortionKind::Rational ? "Distortion.Rational" : "Distortion.Brown")
        << " of camera '" << pc.camera.name << "' cannot be inverted at image position (" << points[firstFailed[b]].x
        << ", " << points[firstFailed[b]].y << ") px: " << why[b];
    // A field of view beyond ~84° to a corner (normalized radius > 10) is rarely meant: most often
    // a pixel size or focal length in mm or µm where metres are asked (pixelSize = {6.9, 6.9}: fx =
    // 0.0017 px, and the message blamed the coefficients alone; the new-user trial of 2026-11-28).
    double corner = 0;
    for (const double x : {-0.5, w - 0.5})
      for (const double y : {-0.5, h - 0.5}) corner = std::max(corner, std::hypot((x - m.cx) / m.fx, (y - m.cy) / m.fy));
    // A telecentric camera's normalized coordinates are metres on the object side (cameras.md): 10 m
    // from the axis is no telecentric field either, and its scale is magnification / pixelSize (an
    // orthographic camera has no focalLength; the camera trial of 2026-11-29 was sent looking for one).
    if (corner > 10 && pc.camera.kind() == CameraKind::Orthographic)
      msg << " (the image's corner lies " << corner << " m from the axis on the object side: fx = " << m.fx
          << " and fy = " << m.fy
          << " px per metre; check magnification and pixelSize (in metres), then the coefficients, whose units are metres' (k1 in m^-2, k2 in m^-4, p1 and p2 in m^-1))";
    else if (corner > 10)
      msg << " (the image's corner lies at a normalized radius of " << corner << ", " << std::atan(corner) * 180 / kPi
          << " degrees off the axis: fx = " << m.fx << " px, fy = " << m.fy
          << " px; check focalLength and pixelSize, both in metres, then the coefficients)";
    else
      msg << " (check the coefficients)";
    throw InputError(pc.camera.where, msg.str());
  }
  const std::lock_guard<std::mutex> lock(mutex);
  if (accepted.size() == kRemembered) accepted.erase(accepted.begin());
  accepted.push_back(key);
}

PreparedCamera prepareCamera(const Camera& sceneCamera, int downscale) {
  PreparedCamera pc;
  pc.camera = downscaled(sceneCamera, downscale);
  pc.model = pinholeModel(pc.camera);
  const auto& m = pc.model;
  pc.rotationCameraFromWorld = glm::transpose(m.worldFromCamera);
  pc.translationCameraFromWorld = -(pc.rotationCameraFromWorld * m.centre);
  checkDistortionInvertible(pc);
  return pc;
}

// Bézier patches, sub-patches and BVH of a Shape.Nurbs; its (u, v) are the normalized knot domain.
// The control points are re-centred on the middle of their bounds, `centre` (returned), which the
// caller puts back into the object's transform: a specimen placed 1 km from the origin by its
// control points keeps small coordinates in its own frame, where the GPU searches in `real`.
std::shared_ptr<const PreparedNurbs> prepareNurbsShape(const Shape& s, dvec3& centre) {
  DS_CHECK(s.nurbs != nullptr, "Shape.Nurbs without its surface");
  NurbsSurface local = *s.nurbs;
  dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const dvec3& p : local.controlPoints) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  centre = 0.5 * (lo + hi);
  for (dvec3& p : local.controlPoints) p -= centre;
  try {
    return std::make_shared<const PreparedNurbs>(prepareNurbs(local));
  } catch (const InputError& e) {
    throw InputError(s.where, e.what());
  }
}

// A calibration target none of whose features lies in front of a camera cannot calibrate it: a
// pose behind the camera is an error in the scene, not an empty image.
void checkTargetInFront(const PreparedObject& o, const Object& so, const std::vector<PreparedCamera>& cameras) {
  for (const PreparedCamera& c : cameras) {
    bool anyInFront = false;
    for (const TargetFeature& f : o.target->features) {
      const dvec4 world = o.worldFromTarget * dvec4(f.target_m, 1);
      anyInFront |= (c.rotationCameraFromWorld * dvec3(world) + c.translationCameraFromWorld).z > 0;
    }
    if (!anyInFront)
      throw InputError(so.where, "target '" + so.name + "' lies behind camera '" + c.camera.name +
                                     "': none of its features is in front of it (check the target's pose)");
  }
}

// A point that the homography sends to infinity cannot see (or light) the object.
// An affine map keeps w = 1: it has no singular plane (a light 1e12 m away was refused for an
// untransformed plate, its relative test failing on the coordinates' size: radiometry audit).
void checkFinite(const PreparedObject& o, const Object& so, const dvec3& p, const std::string& what) {
  if (isAffine(o.worldFromObject)) return;
  const dvec4 a = o.objectFromWorld.point(p);
  if (!(std::abs(a.w) > 1e-12 * (std::abs(a.x) + std::abs(a.y) + std::abs(a.z))))
    throw InputError(so.where, "the transform of object '" + so.name + "' sends " + what +
                                   " to infinity (it lies on the homography's singular plane)");
}

// With a projective transform, a ray whose origin lies on the other side than the object of the plane
// that the map sends to infinity reaches the object only after crossing that plane: its image in the
// object frame runs out to infinity and comes back from the other end, and both renderers search
// the first part alone (geometry/homography.h), so the object would be missing from the image (or
// from the shadow rays) without a word. Refused, naming the point. The object's side: the sign of
// w of its frame's origin mapped to the world (H's bottom row · (0, 0, 0, 1)); a point's: that of
// w of the point mapped into the object frame (equal signs: the ray's w stays of one sign up to the
// object, being linear in the ray parameter).
void checkSameSide(const PreparedObject& o, const Object& so, const dvec3& p, const std::string& what) {
  const double objectSide = o.worldFromObject[3][3];
  if (isAffine(o.worldFromObject) || objectSide == 0) return;
  const double pointSide = o.objectFromWorld.point(p).w;
  if ((pointSide > 0) != (objectSide > 0))
    throw InputError(so.where, "the transform of object '" + so.name + "' is projective and " + what +
                                   " lies beyond the plane it sends to infinity, on the other side than the "
                                   "object: rays from there would miss it (keep it on the object's side)");
}

// The key of a file texture in prepareScene's table: one entry per path and spline (kernel, borders).
std::string textureKey(const textures::File& t) {
  return std::to_string(splineCode(t.interpolation, t.wrap)) + ":" + t.path;
}

// PrepareOptions::textureData false: the table's entry names the texture, without reading it.
int nameTexture(const textures::File& t, std::vector<PreparedTexture>& textures, std::map<std::string, int>& byPath) {
  if (auto it = byPath.find(textureKey(t)); it != byPath.end()) return it->second;
  PreparedTexture named;
  named.path = t.path;
  named.interpolation = t.interpolation;
  named.wrap = t.wrap;
  textures.push_back(std::move(named));
  return byPath[textureKey(t)] = int(textures.size()) - 1;
}

// One prepared texture per (file, interpolation, wrap): the coefficients depend on the kernel and
// the borders.
// The texture of `file` (the bytes of t.path) prepared for `t`'s kernel: from the disk cache (keyed
// by the bytes' digest) or decoded, checked and prefiltered. `*readPath` says whether the decoder
// read the path instead of the bytes (files/image_io.h). Its stamp is left for the caller to set.
PreparedTexture readTexture(const textures::File& t, const FileBytes& file, const SourceLoc& where,
                            const TextureDiskCache* disk, bool* readPath) {
  *readPath = false;
  // Across processes: the disk cache, keyed by the file's content.
  const std::string digest = disk ? TextureDiskCache::digestOf(file.bytes) : "";
  if (disk)
    if (auto stored = disk->find(digest, t.path, t.interpolation, t.wrap)) return std::move(*stored);
  GrayImage image;
  try {
    image = decodeGrayImage(t.path, file.bytes, readPath);
  } catch (const InputError& e) {
    throw InputError(where, std::string("Texture.File: ") + e.what());
  }
  // Texels are reflectances: finite and >= 0 (as Texture.Speckle's dark and light). One NaN would
  // spread through the B-spline prefilter into every pixel of the image. At most 1e30: the GPU's
  // df64 splits a float a as 4097·a (Dekker), which overflows above ~8e34, and the prefilter can
  // multiply a texel by up to 7.5 (quintic, alternating texels: 120 / (66 − 52 + 2)); 1e30 leaves
  // that and a colour or light of up to ~1e3 within every precision (the texture audit of
  // 2026-11-28: a texel of 1e35 made df64's radiance NaN, refused late with a misleading cause).
  constexpr double kMaxTexel = 1e30;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const double v = image.pixels[i];
    if (std::isfinite(v) && v >= 0 && v <= kMaxTexel) continue;
    const std::size_t x = i % std::size_t(image.width), y = i / std::size_t(image.width);
    const std::string what = !std::isfinite(v) ? "non-finite texel"
                             : v < 0           ? "negative texel " + shortestNumber(v)
                                               : "texel " + shortestNumber(v) + " above 1e30";
    throw InputError(where, "Texture.File: " + t.path + ": " + what + " at (" + std::to_string(x) + ", " +
                                std::to_string(y) +
                                ") (x, y from the top-left; texels are reflectances: finite, >= 0 and at most 1e30)");
  }
  PreparedTexture pt;
  pt.path = t.path;
  pt.width = image.width;
  pt.height = image.height;
  pt.interpolation = t.interpolation;
  pt.wrap = t.wrap;
  bsplinePrefilter(image.pixels, pt.width, pt.height, t.interpolation, t.wrap);
  pt.coefficients = std::make_shared<const std::vector<double>>(std::move(image.pixels));
  // Stored under the digest of the bytes decoded (a path read: when the file is still those bytes).
  if (disk && !digest.empty() && (!*readPath || fileStamp(t.path) == file.stamp)) disk->store(digest, pt);
  return pt;
}

int loadTexture(const textures::File& t, const SourceLoc& where, std::vector<PreparedTexture>& textures,
                std::map<std::string, int>& byPath, TextureCache* cache) {
  const std::string key = textureKey(t);
  if (auto it = byPath.find(key); it != byPath.end()) return it->second;
  if (cache)
    if (auto cached = cache->find(t.path, t.interpolation, t.wrap)) {
      textures.push_back(std::move(*cached));
      return byPath[key] = int(textures.size()) - 1;
    }
  const TextureDiskCache* disk = cache && cache->disk().enabled() ? &cache->disk() : nullptr;
  // The file's bytes are read once, under one stamp (files/file_bytes.h), and decoded from memory:
  // the coefficients, the digest and the CRC are of one content, however long the decoding takes.
  // Read again (three readings at most) when it was written in place while read; a file renamed
  // over it meanwhile is no change (the bytes are the file opened).
  constexpr int kReadings = 3;
  for (int reading = 1;; ++reading) {
    std::optional<FileBytes> file;
    try {
      file = readFileBytes(t.path);
    } catch (const InputError& e) {
      throw InputError(where, std::string("Texture.File: ") + e.what());
    }
    if (file) {
      bool readPath = false;
      std::optional<PreparedTexture> pt;
      try {
        pt = readTexture(t, *file, where, disk, &readPath);
      } catch (const InputError&) {
        // Bytes that do not decode: a file being written (its stamp has moved since: read it
        // again, and say why if it kept changing), or a file bad as it is.
        if (fileStamp(t.path) == file->stamp) throw;
      }
      // A format decoded from its path (files/image_io.h): the file must still be the one read.
      if (pt && (!readPath || fileStamp(t.path) == file->stamp)) {
        pt->stamp = file->stamp;
        pt->contentCrc32 = crc32Of(file->bytes);
        if (cache) cache->insert(*pt);
        textures.push_back(std::move(*pt));
        return byPath[key] = int(textures.size()) - 1;
      }
    }
    if (reading == kReadings)
      throw InputError(where, "Texture.File: " + t.path + ": the file changed while it was read, " +
                                  std::to_string(kReadings) + " times: it is being written (render once it is complete)");
  }
}

}  // namespace

bool PreparedTexture::fileUnchanged() const { return fileStillHolds(path, stamp, contentCrc32); }

void forEachInputFile(const PreparedScene& scene,
                      const std::function<void(const char* kind, const FileContent& file)>& visit) {
  for (const PreparedTexture& t : scene.textures) visit("texture", FileContent{t.path, t.stamp, t.contentCrc32});
  for (const PreparedObject& o : scene.objects)
    if (o.deformation && o.deformation->meshFile) visit("mesh", *o.deformation->meshFile);
}

PinholeModel<double> pinholeModel(const Camera& c) {
  PinholeModel<double> m;
  m.kind = c.kind();
  // Distance from the lens to the sensor (the chief ray's pinhole focal length), or for a
  // telecentric lens the magnification: fx = it / pixel size (cameras/<kind>.h).
  const double scale = c.focalScale();
  std::visit([&m](const auto& kind) { kind.prepareLens(m); }, c.model);
  m.fx = scale / c.pixelSize_m.x;
  m.fy = scale / c.pixelSize_m.y;
  m.cx = c.principalPoint_px.x;
  m.cy = c.principalPoint_px.y;
  const Distortion& d = c.distortion;
  m.distorted = d.kind != DistortionKind::None;
  m.brown = {d.k1, d.k2, d.k3, d.p1, d.p2, d.k4, d.k5, d.k6, d.s1, d.s2, d.s3, d.s4};
  m.worldFromCamera = dmat3(c.worldFromCamera);
  m.centre = dvec3(c.worldFromCamera[3]);
  return m;
}

PreparedScene prepareScene(const Scene& scene, const PrepareOptions& options) {
  if (options.downscale < 1) throw InputError(optionName("--downscale") + " must be >= 1");
  PreparedScene ps;
  ps.file = scene.file;
  ps.keepAlive = scene.keepAlive;
  for (const Camera& c : scene.cameras) ps.cameras.push_back(prepareCamera(c, options.downscale));
  for (const Light& l : scene.lights) {
    PreparedLight pl;
    pl.kind = l.kind;
    pl.position_m = l.position_m;
    pl.intensity = l.intensity;
    if (l.kind == LightKind::Spot) {
      pl.direction = glm::normalize(l.direction);
      pl.cosOuter = std::cos(l.outerAngle_rad);
      pl.cosInner = std::cos(l.innerAngle_rad);
    }
    ps.lights.push_back(pl);
  }
  for (const StereoRig& r : scene.rigs) {
    PreparedRig pr;
    pr.name = r.name;
    for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
      if (scene.cameras[c].name == r.left) pr.left = int(c);
      if (scene.cameras[c].name == r.right) pr.right = int(c);
    }
    DS_CHECK(pr.left >= 0 && pr.right >= 0, "rig '" + r.name + "' names a camera the scene lacks");
    ps.rigs.push_back(std::move(pr));
  }

  std::map<std::string, int> texturesByPath;
  bool anyLit = false;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& so = scene.objects[i];
    PreparedObject o;
    o.name = so.name;
    o.id = std::uint32_t(i + 1);
    o.geometry.analytic = so.shape.analytic;
    if (so.shape.kind() == ShapeKind::Nurbs) {
      o.nurbs = prepareNurbsShape(so.shape, o.shapeOffset_m);
      o.surface = so.shape.nurbs;
      o.deformation = so.shape.deformation;
      o.geometry.nurbs = o.nurbs.get();
    }
    o.shader = so.shader.model;
    o.albedo = luminance(so.shader.color);
    anyLit |= reflectance::kindInfo(o.shader).lit;
    o.texture = so.texture.model;
    if (auto* file = std::get_if<textures::File>(&o.texture); file && !options.textureData) {
      file->index = nameTexture(*file, ps.textures, texturesByPath);
    } else if (file) {
      // The image, decoded and prefiltered once per path and kernel, shared with the texture table.
      file->index = loadTexture(*file, so.texture.where, ps.textures, texturesByPath, options.textureCache);
      const PreparedTexture& image = ps.textures[std::size_t(file->index)];
      file->coefficients = image.coefficients;
      file->width = image.width;
      file->height = image.height;
    }
    o.worldFromObject = glm::translate(dmat4(1.0), so.shape.location_m) * so.transform *
                        glm::translate(dmat4(1.0), o.shapeOffset_m);
    o.objectFromWorld = ObjectFromWorld::of(o.worldFromObject);
    if (const textures::TargetPattern* pattern = textures::targetPattern(so.texture.model)) {
      // The target's rectangle is centred on rectangleCentre_m of the target frame
      // (Target.* constructors: transform = worldFromTarget · translate(rectangleCentre_m)).
      auto layout = std::make_shared<const TargetLayout>(targetLayout(so.texture.kind(), *pattern));
      textures::targetDrawing(o.texture)->drawn = layout->texture;
      o.worldFromTarget = o.worldFromObject * glm::translate(dmat4(1.0), -layout->rectangleCentre_m);
      o.target = std::move(layout);
      checkTargetInFront(o, so, ps.cameras);
    }
    for (const PreparedCamera& c : ps.cameras) {
      checkFinite(o, so, c.model.centre, "camera '" + c.camera.name + "'");
      checkSameSide(o, so, c.model.centre, "camera '" + c.camera.name + "'");
    }
    for (const Light& l : scene.lights)
      if (l.kind != LightKind::Ambient) checkFinite(o, so, l.position_m, "light '" + l.name + "'");
    ps.objects.push_back(std::move(o));
  }

  ps.features.lights = anyLit && !ps.lights.empty();
  // Shadow rays leave the other objects: their origins too (an object's frame origin stands for it).
  if (ps.features.lights)
    for (std::size_t a = 0; a < ps.objects.size(); ++a)
      for (std::size_t b = 0; b < ps.objects.size(); ++b)
        if (b != a) {
          const dvec4 origin = ps.objects[b].worldFromObject * dvec4(0, 0, 0, 1);
          if (origin.w != 0)
            checkSameSide(ps.objects[a], scene.objects[a], dvec3(origin) / origin.w,
                          "object '" + ps.objects[b].name + "' (which its shadow rays leave)");
        }
  for (const PreparedLight& l : ps.lights) ps.features.lightKinds |= 1u << int(l.kind);
  for (const PreparedCamera& c : ps.cameras) {
    ps.features.distortion |= c.model.distorted;
    ps.features.rationalDistortion |= c.camera.distortion.kind == DistortionKind::Rational;
    ps.features.cameraKinds |= 1u << int(c.camera.kind());
  }
  ps.features.fileTextures = !ps.textures.empty();
  for (const PreparedTexture& t : ps.textures)
    ps.features.quinticTextures |= t.interpolation == Interpolation::Quintic;
  for (const PreparedObject& o : ps.objects) {
    ps.features.shapeKinds |= 1u << int(o.geometry.kind());
    ps.features.speckleTextures |= textures::kindOf(o.texture) == TextureKind::Speckle;
    ps.features.targetTextures |= isTargetTexture(textures::kindOf(o.texture));
    ps.features.shaderKinds |= 1u << int(reflectance::kindOf(o.shader));
    if (o.nurbs)
      for (const BezierPatch& p : o.nurbs->patches)
        ps.features.nurbsDegree = std::max({ps.features.nurbsDegree, p.degreeU, p.degreeV});
  }
  return ps;
}

}  // namespace dicsynth
