#include "render/ground_truth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <utility>

#include "core/parallel.h"
#include "core/warning.h"
#include "geometry/material_point.h"
#include "nurbs/nurbs.h"
#include "render/image_point.h"

namespace dicsynth {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const dvec2 kNaN2{kNaN, kNaN};


// Rows in parallel: one pixel's work is a few traced rays at most.
template <class Body>
void forEachPixel(int width, int height, Body body) {
  parallelFor(std::size_t(height), [&](std::size_t y) {
    for (int x = 0; x < width; ++x) body(std::size_t(y) * std::size_t(width) + std::size_t(x), x, int(y));
  });
}

int objectIndexByName(const PreparedScene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].name == name) return int(i);
  return -1;
}

std::vector<dvec2> computeDistortionField(const PreparedCamera& pc) {
  const Camera& c = pc.camera;
  std::vector<dvec2> field(std::size_t(c.width_px) * std::size_t(c.height_px), dvec2(0));
  const auto& m = pc.model;
  if (!m.distorted) return field;
  // Each pixel centre is a distorted position; its undistorted position is K·undistort(K⁻¹x).
  // prepareScene checked that the inverse round-trips to < 1e-9 px over the whole image.
  // Rows on all cores; along a row eight pixels at a time in lockstep (undistortLockstep: the same
  // results as undistort() one by one, ~1.5x faster). A row's last block repeats its last pixel in
  // the lanes past the end (inverted, not written).
  constexpr int kLanes = 8;
  const int w = c.width_px;
  parallelFor(std::size_t(c.height_px), [&](std::size_t yIndex) {
    const int y = int(yIndex);
    dvec2* row = field.data() + yIndex * std::size_t(w);
    dvec2 target[kLanes], ideal[kLanes];
    for (int x0 = 0; x0 < w; x0 += kLanes) {
      for (int l = 0; l < kLanes; ++l) target[l] = dvec2{(std::min(x0 + l, w - 1) - m.cx) / m.fx, (y - m.cy) / m.fy};
      undistortLockstep<kLanes>(m.brown, target, ideal);
      for (int l = 0; l < kLanes && x0 + l < w; ++l)
        row[x0 + l] = dvec2{x0 + l, y} - dvec2{m.fx * ideal[l].x + m.cx, m.fy * ideal[l].y + m.cy};
    }
  });
  return field;
}

// The field depends only on the image size, the intrinsics and the distortion coefficients, which
// the points of a sweep rarely change, while computing it (a Newton inversion per pixel, in double)
// was a visible share of a sweep point's CPU time (bench/RESULTS.md, "Sweeps"). So the last two
// fields computed are kept, keyed by exactly those numbers (compared exactly), so that a sweep
// computes each camera's once; two entries: the two cameras of a stereo rig. Shared, not copied:
// a copy was 31 MB for 1600 × 1200, ~0.014 s of Figure 1's truth phase (bench/RESULTS.md).
std::shared_ptr<const std::vector<dvec2>> distortionField(const PreparedCamera& pc) {
  const auto& m = pc.model;
  const auto& k = m.brown;
  using Key = std::array<double, 19>;
  const Key key = {double(pc.camera.width_px), double(pc.camera.height_px), m.fx, m.fy, m.cx, m.cy,
                   m.distorted ? 1.0 : 0.0, k.k1, k.k2, k.k3, k.p1, k.p2, k.k4, k.k5, k.k6, k.s1, k.s2, k.s3, k.s4};
  static std::mutex mutex;
  static std::deque<std::pair<Key, std::shared_ptr<const std::vector<dvec2>>>> kept;  // newest first
  {
    std::lock_guard lock(mutex);
    for (const auto& [kk, field] : kept)
      if (kk == key) return field;
  }
  auto field = std::make_shared<const std::vector<dvec2>>(computeDistortionField(pc));
  std::lock_guard lock(mutex);
  kept.emplace_front(key, field);
  if (kept.size() > 2) kept.pop_back();
  return field;
}

// Whether an object's surface is a Nurbs.deform fit: only then has fieldError values, and only
// then does it read the reference frame's material points.
bool anyDeformed(const PreparedScene& scene) {
  for (const PreparedObject& o : scene.objects)
    if (o.deformation) return true;
  return false;
}

// x(m) of the header comment: NaN where the camera has no image position for the point.
dvec2 seenAt(const ImagePoint& p) { return p.inFront && !p.folded ? p.pixel_px : kNaN2; }

dvec2 projectPoint(const PreparedCamera& camera, dvec3 world_m) { return seenAt(projectToImage(camera, world_m)); }

// Whether two views see the same side of a surface (sideSeen): a view of the other side of a
// zero-thickness surface sees another material point of the specimen (its other face), so the
// mask is 0 there whatever the ray meets first. Where either side is unknown (0), the ray decides.
bool sameSide(int a, int b) { return a == 0 || b == 0 || a == b; }

// The side of the surface `camera` sees at the material point (sideSeen from its chief ray's origin).
int sideSeenBy(const PreparedCamera& camera, const MaterialPointFrame& frame) {
  return sideSeen(frame, chiefRayOrigin(camera.model, frame.point_m));
}

// Points of one camera whose visibility is to be traced, by pixel: object −1 where none is.
struct VisibilityCandidates {
  std::vector<dvec3> point_m;
  std::vector<int> object;
  explicit VisibilityCandidates(std::size_t n) : point_m(n, dvec3(0)), object(n, -1) {}
};

// mask[i] = 1 where candidate i is reached first by `camera`'s chief ray: all candidates in one
// call of the tracer (the rendering device), or of the CPU reference when there is none.
void fillVisibilityMask(const VisibilityTracer& tracer, const PreparedScene& scene, std::size_t camera,
                        const VisibilityCandidates& candidates, std::vector<float>& mask) {
  std::vector<dvec3> points;
  std::vector<int> objects;
  std::vector<std::size_t> pixels;
  for (std::size_t i = 0; i < candidates.object.size(); ++i) {
    if (candidates.object[i] < 0) continue;
    points.push_back(candidates.point_m[i]);
    objects.push_back(candidates.object[i]);
    pixels.push_back(i);
  }
  const std::vector<std::uint8_t> reached =
      tracer ? tracer(scene, camera, points, objects, kVisibilityTolerance)
             : reachesFirstCpu(scene, camera, points, objects, kVisibilityTolerance);
  DS_CHECK(reached.size() == points.size(), "visibility tracer answered the wrong number of points");
  for (std::size_t k = 0; k < pixels.size(); ++k) mask[pixels[k]] = reached[k] ? 1.0f : 0.0f;
}

}  // namespace

ReferenceFrame::ReferenceFrame(int frame, PreparedScene scene, const RenderResult& result, bool otherFrames,
                               bool motion)
    : frame_(frame), scene_(std::move(scene)) {
  DS_CHECK(result.cameras.size() == scene_.cameras.size(), "reference render and scene disagree");
  if (!motion) return;
  const bool points = otherFrames || anyDeformed(scene_);  // who reads material and position_m (ground_truth.h)
  for (std::size_t c = 0; c < result.cameras.size(); ++c) {
    const CameraImage& image = result.cameras[c];
    DS_CHECK(image.hasGeometry(), "motion truth of a render without geometry (RenderOptions::geometry)");
    View v;
    v.camera = image.cameraName;
    v.width_px = image.width_px;
    v.height_px = image.height_px;
    const std::size_t n = image.pixelCount();
    v.object.assign(n, -1);
    if (points) {
      v.material.assign(n, kNaN2);
      v.position_m.assign(n, dvec3(kNaN));
      v.side.assign(n, 0);
    }
    if (otherFrames) v.pixel_px.assign(n, kNaN2);
    const PreparedCamera& camera = scene_.cameras[c];
    forEachPixel(image.width_px, image.height_px, [&](std::size_t i, int, int) {
      if (image.objectId[i] == 0) return;
      const int o = int(image.objectId[i]) - 1;
      const PreparedObject& obj = scene_.objects[std::size_t(o)];
      const dvec2 m = materialCoordinates(obj, image.uv[i], image.position_m[i]);
      if (!points) {
        if (hasMaterialPoint(obj, m)) v.object[i] = o;
        return;
      }
      const auto f = worldFrameOfMaterial(obj, m);
      if (!f) return;
      v.object[i] = o;
      v.material[i] = m;
      v.position_m[i] = f->point_m;
      v.side[i] = std::int8_t(sideSeenBy(camera, *f));
      if (otherFrames) v.pixel_px[i] = projectPoint(camera, f->point_m);
    });
    views_.push_back(std::move(v));
  }
}

const ReferenceFrame::View* ReferenceFrame::view(const std::string& camera) const {
  for (const View& v : views_)
    if (v.camera == camera) return &v;
  return nullptr;
}

// fieldError (ground_truth.h) at the reference view's pixels. The field is called once per
// deformed object with all its pixels' points, in pixel order (a Lua function runs serially).
std::vector<dvec3> fieldErrors(const ReferenceFrame::View& view, const std::vector<int>& objectNow,
                               const PreparedScene& scene) {
  const std::size_t n = view.object.size();
  DS_CHECK(view.material.size() == n, "fieldError of a reference frame built without its material points");
  std::vector<dvec3> error(n, dvec3(kNaN));
  std::vector<std::vector<std::size_t>> pixels(scene.objects.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (view.object[i] < 0) continue;
    const int o = objectNow[std::size_t(view.object[i])];
    if (o < 0) continue;
    if (scene.objects[std::size_t(o)].deformation) pixels[std::size_t(o)].push_back(i);
    else error[i] = dvec3(0);
  }
  for (std::size_t o = 0; o < pixels.size(); ++o) {
    if (pixels[o].empty()) continue;
    const PreparedObject& object = scene.objects[o];
    const Deformation& deformation = *object.deformation;
    const std::size_t k = pixels[o].size();
    std::vector<dvec3> S(k), F(k);
    parallelFor(k, [&](std::size_t j) {
      const dvec2 m = view.material[pixels[o][j]];
      S[j] = evaluateNurbs<double>(*deformation.reference, m.x, m.y).point;
      F[j] = evaluateNurbs<double>(*object.surface, m.x, m.y).point;
    });
    const std::vector<dvec3> d = deformation.field(S);
    // Both points through the object's transform (a homography in general: no linear shortcut).
    auto world = [&](const dvec3& shapePoint) {
      const dvec4 h = object.worldFromObject * dvec4(shapePoint - object.shapeOffset_m, 1);
      return dvec3(h) / h.w;
    };
    parallelFor(k, [&](std::size_t j) { error[pixels[o][j]] = world(F[j]) - world(S[j] + d[j]); });
  }
  return error;
}

DerivedTruth deriveTruth(const ReferenceFrame& reference, int frame, const PreparedScene& scene,
                         const RenderResult& result, std::size_t cameraIndex, const LayerSet& layers,
                         const VisibilityTracer& visibility) {
  const PreparedCamera& camera = scene.cameras[cameraIndex];
  const CameraImage& image = result.cameras[cameraIndex];
  DerivedTruth truth;
  truth.referenceFrame = reference.frame();
  if (layers.has(Layer::Distortion)) truth.distortion_px = distortionField(camera);

  // Motion: follow each reference pixel's material point into this frame.
  const ReferenceFrame::View* view = reference.view(camera.camera.name);
  const bool flow = layers.has(Layer::Flow);
  const bool motion = layers.anyMotion();
  const bool sameSize = view && view->width_px == image.width_px && view->height_px == image.height_px;
  if (motion && !sameSize) {
    // The motion layers are stored at the reference frame's pixels, in this frame's image: without
    // a reference image of the same size they have no place. Said, not silent: the file lacked
    // them without a word (the motion audit of 2026-11-28).
    const std::string why =
        view ? "is " + std::to_string(image.width_px) + "x" + std::to_string(image.height_px) + " px, " +
                   std::to_string(view->width_px) + "x" + std::to_string(view->height_px) + " in the reference frame " +
                   std::to_string(reference.frame())
             : "is not in the reference frame " + std::to_string(reference.frame());
    warnAtMost("motion layers without reference", 10,
               "camera '" + camera.camera.name + "' " + why + ": frame " + std::to_string(frame) +
                   " has no disp, flow or fieldError for it (they are stored at the reference frame's pixels)",
               " (further cameras without motion layers not reported)");
  }
  if (motion && sameSize) {
    const std::size_t n = image.pixelCount();
    // The three arrays filled side by side: ~44 bytes per pixel first touched here, 0.028 s on one
    // thread for 1600 × 1200 (bench/RESULTS.md, "Truth without copies"). Small images in line.
    const auto fill = [&](std::size_t k) {
      if (k == 0) truth.displacement_m.assign(n, dvec3(kNaN));
      else if (k == 1) truth.flow_px.assign(n, kNaN2);
      else truth.flowMask.assign(n, 0.0f);
    };
    if (n < (std::size_t(1) << 16)) {
      for (std::size_t k = 0; k < 3; ++k) fill(k);
    } else {
      parallelFor(3, fill);
    }
    // Objects are matched by name: a frame may add or drop objects, which renumbers them.
    std::vector<int> objectNow(reference.scene().objects.size());
    for (std::size_t o = 0; o < objectNow.size(); ++o)
      objectNow[o] = objectIndexByName(scene, reference.scene().objects[o].name);
    const bool isReference = frame == reference.frame();
    DS_CHECK(isReference || view->pixel_px.size() == n, "reference frame built without otherFrames");
    VisibilityCandidates seen(flow && !isReference ? n : 0);
    forEachPixel(image.width_px, image.height_px, [&](std::size_t i, int, int) {
      if (view->object[i] < 0) return;
      if (isReference) {
        truth.displacement_m[i] = dvec3(0);
        truth.flow_px[i] = dvec2(0);
        truth.flowMask[i] = 1.0f;
        return;
      }
      const int o = objectNow[std::size_t(view->object[i])];
      if (o < 0) return;
      const auto f = worldFrameOfMaterial(scene.objects[std::size_t(o)], view->material[i]);
      if (!f) return;
      truth.displacement_m[i] = f->point_m - view->position_m[i];
      if (!flow) return;  // its visibility is the costly part: traced only when asked for
      const ImagePoint now = projectToImage(camera, f->point_m);
      truth.flow_px[i] = seenAt(now) - view->pixel_px[i];
      if (!now.inImage) return;  // mask 0
      if (!sameSide(view->side[i], sideSeenBy(camera, *f))) return;  // mask 0
      seen.point_m[i] = f->point_m;
      seen.object[i] = o;
    });
    if (flow && !isReference) fillVisibilityMask(visibility, scene, cameraIndex, seen, truth.flowMask);
    if (layers.has(Layer::FieldError) && anyDeformed(scene)) truth.fieldError_m = fieldErrors(*view, objectNow, scene);
  }

  // Disparity: this pixel's material point seen by the rig's other camera.
  const int other = rigPartner(scene, cameraIndex);
  if (other >= 0 && layers.has(Layer::Disparity)) {
    DS_CHECK(image.hasGeometry(), "disparity of a render without geometry (RenderOptions::geometry)");
    const PreparedCamera& otherCamera = scene.cameras[std::size_t(other)];
    truth.disparityCamera = otherCamera.camera.name;
    const std::size_t n = image.pixelCount();
    truth.disparity_px.assign(n, kNaN2);
    truth.disparityMask.assign(n, 0.0f);
    VisibilityCandidates seen(n);
    forEachPixel(image.width_px, image.height_px, [&](std::size_t i, int, int) {
      if (image.objectId[i] == 0) return;
      const int o = int(image.objectId[i]) - 1;
      const PreparedObject& obj = scene.objects[std::size_t(o)];
      const auto f = worldFrameOfMaterial(obj, materialCoordinates(obj, image.uv[i], image.position_m[i]));
      if (!f) return;
      const ImagePoint there = projectToImage(otherCamera, f->point_m);
      truth.disparity_px[i] = seenAt(there) - projectPoint(camera, f->point_m);
      if (!there.inImage) return;  // mask 0
      if (!sameSide(sideSeenBy(camera, *f), sideSeenBy(otherCamera, *f))) return;  // mask 0
      seen.point_m[i] = f->point_m;
      seen.object[i] = o;
    });
    fillVisibilityMask(visibility, scene, std::size_t(other), seen, truth.disparityMask);
    for (float v : truth.disparityMask) truth.disparityVisibleCount += v > 0 ? 1 : 0;
  }
  return truth;
}

}  // namespace dicsynth
