#include "io/feature_files.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <variant>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/json.h"
#include "core/warning.h"
#include "render/target_features.h"

namespace dicsynth {

// A target drawn on both sides is seen from its back too, mirrored, and its features stay visible;
// a printed one would show a blank back, and a detector labels the mirrored pattern as a front view
// with a false pose (the calibration audit of 2026-11-28). Said once per run (per process in the
// CLI, per call of the Python module's `features`: core/warning.h). The back faces
// +z of the target frame: a ray meets it when it travels against z (ray · z < 0); the rays are the
// chief rays from the camera centre to the visible features, or the axis of a telecentric camera.
namespace {

void warnIfSeenFromBack(const PreparedScene& scene, std::size_t camera, int frame,
                        const std::vector<TargetTruth>& targets) {
  const PreparedCamera& cam = scene.cameras[camera];
  const bool telecentric = std::holds_alternative<cameras::Orthographic>(cam.camera.model);
  for (const TargetTruth& target : targets) {
    const dvec3 zCamera = cam.rotationCameraFromWorld * dvec3(scene.objects[target.object].worldFromTarget[2]);
    for (const FeatureTruth& f : target.features) {
      if (!f.visible()) continue;
      const dvec3 ray = telecentric ? dvec3(0, 0, 1)
                                    : cam.rotationCameraFromWorld * f.world_m + cam.translationCameraFromWorld;
      if (glm::dot(ray, zCamera) >= 0) continue;
      warnAtMost("target seen from its back", 1,
                 "camera " + cam.camera.name + ", frame " + std::to_string(frame) + ": target '" + target.name +
                     "' is seen from its back: a printed target would show a blank back there, while the render "
                     "draws its pattern mirrored and the feature files list its features as visible (turn the "
                     "target or the camera)");
      return;
    }
  }
}

// A target none of whose features is visible, or whose visible features lie closer together in
// the image than a detector resolves: the calibration trial of 2026-11-28 gave `focalLength = 16`
// (mm for m: 0 of 70 features in the image), `squareSize = 10` (1 of 70) and `pixelSize = {5.5,
// 5.5}` (µm for m: the board within one pixel, its 70 features all listed as visible) and heard
// nothing but, at most, that the image is background only. Said at most 3 times per run.
void warnIfUnseen(const PreparedScene& scene, std::size_t camera, int frame, const std::vector<TargetTruth>& targets) {
  const std::string where = "camera " + scene.cameras[camera].camera.name + ", frame " + std::to_string(frame) + ": ";
  const std::string units = "check the camera's pose, focalLength and pixelSize and the target's location and size, all in metres";
  const std::string further = " (further warnings of unseen targets not reported)";
  for (const TargetTruth& target : targets) {
    std::size_t behind = 0, outside = 0, hidden = 0, visible = 0;
    for (const FeatureTruth& f : target.features) {
      if (!f.inFront) ++behind;
      else if (!f.inImage) ++outside;
      else if (!f.unoccluded) ++hidden;
      else ++visible;
    }
    if (visible == 0 && !target.features.empty()) {
      warnAtMost("target unseen", 3,
                 where + "no feature of target '" + target.name + "' is visible (of " +
                     std::to_string(target.features.size()) + ": " + std::to_string(behind) + " behind the camera, " +
                     std::to_string(outside) + " outside the image, " + std::to_string(hidden) +
                     " hidden by an object); " + units,
                 further);
      continue;
    }
    // The median distance between neighbouring visible features (same row, next column), px.
    std::vector<double> gaps;
    for (std::size_t i = 0; i + 1 < target.features.size(); ++i) {
      const FeatureTruth &a = target.features[i], &b = target.features[i + 1];
      if (a.row == b.row && a.visible() && b.visible()) gaps.push_back(glm::length(b.pixel_px - a.pixel_px));
    }
    if (gaps.empty()) continue;
    std::nth_element(gaps.begin(), gaps.begin() + std::ptrdiff_t(gaps.size() / 2), gaps.end());
    const double gap_px = gaps[gaps.size() / 2];
    // 2 px: a checkerboard's squares or a grid's dots that small are not resolved by a corner or
    // blob detector (OpenCV's findChessboardCornersSB wants several pixels per square).
    std::ostringstream gap;
    gap.precision(3);
    gap << gap_px;
    if (gap_px < 2)
      warnAtMost("target unseen", 3,
                 where + "the features of target '" + target.name + "' lie " + gap.str() +
                     " px apart in the image (median of neighbours), closer than a detector resolves; " + units,
                 further);
  }
}

}  // namespace

void warnAboutTargetViews(const PreparedScene& scene, std::size_t camera, int frame,
                          const std::vector<TargetTruth>& targets) {
  warnIfSeenFromBack(scene, camera, frame, targets);
  warnIfUnseen(scene, camera, frame, targets);
}

const char* targetKindName(TextureKind kind) {
  return kind == TextureKind::Checkerboard ? "checkerboard" : "circle_grid";
}

namespace {

// Exact (core/exact_number.h); NaN as "nan" in CSV, whatever its sign bit.
std::string csvNumber(double v) { return std::isnan(v) ? "nan" : exactNumber(v); }

Json::Value jsonVector(std::initializer_list<double> values) {
  Json::Value out(Json::arrayValue);
  for (double v : values) out.append(json::value(v));  // null for NaN
  return out;
}

// Counts (sizes in pixels, OpenCV's patternSize) stay integers: readers hand them to OpenCV.
Json::Value jsonIntegers(std::initializer_list<int> values) {
  Json::Value out(Json::arrayValue);
  for (int v : values) out.append(v);
  return out;
}

std::string csvText(const std::vector<TargetTruth>& targets) {
  std::ostringstream s;
  s << "target,index,row,col,target_x_m,target_y_m,target_z_m,world_x_m,world_y_m,world_z_m,x_px,y_px,"
       "depth_m,in_front,in_image,unoccluded,visible\n";
  for (const TargetTruth& t : targets)
    for (const FeatureTruth& f : t.features) {
      s << t.name << ',' << f.index << ',' << f.row << ',' << f.col;
      for (double v : {f.target_m.x, f.target_m.y, f.target_m.z, f.world_m.x, f.world_m.y, f.world_m.z,
                       f.pixel_px.x, f.pixel_px.y, f.depth_m})
        s << ',' << csvNumber(v);
      s << ',' << int(f.inFront) << ',' << int(f.inImage) << ',' << int(f.unoccluded) << ',' << int(f.visible())
        << '\n';
    }
  return s.str();
}

std::string jsonText(const PreparedScene& scene, std::size_t camera, int frame,
                     const std::vector<TargetTruth>& targets) {
  const PreparedCamera& c = scene.cameras[camera];
  Json::Value d(Json::objectValue);
  d["scene"] = scene.file;
  d["camera"] = c.camera.name;
  d["frame"] = frame;
  d["image_size"] = jsonIntegers({c.camera.width_px, c.camera.height_px});
  Json::Value& list = d["targets"] = Json::Value(Json::arrayValue);
  for (const TargetTruth& t : targets) {
    const TargetLayout& l = *t.layout;
    const dmat3& R = t.R_cameraFromTarget;
    const dvec3& tv = t.t_cameraFromTarget_m;
    Json::Value target(Json::objectValue);
    target["name"] = t.name;
    target["kind"] = targetKindName(l.kind);
    target["pattern_size"] = jsonIntegers({l.perRow, l.rows});
    target["asymmetric"] = l.pattern.asymmetric;
    target["spacing_m"] = json::value(l.pattern.spacing_m);
    target["R_camera_from_target"] =
        jsonVector({R[0][0], R[1][0], R[2][0], R[0][1], R[1][1], R[2][1], R[0][2], R[1][2], R[2][2]});  // row-major
    target["t_camera_from_target_m"] = jsonVector({tv.x, tv.y, tv.z});
    Json::Value& features = target["features"] = Json::Value(Json::arrayValue);
    for (const FeatureTruth& f : t.features) {
      Json::Value e(Json::objectValue);
      e["index"] = f.index;
      e["row"] = f.row;
      e["col"] = f.col;
      e["target_m"] = jsonVector({f.target_m.x, f.target_m.y, f.target_m.z});
      e["world_m"] = jsonVector({f.world_m.x, f.world_m.y, f.world_m.z});
      e["pixel"] = jsonVector({f.pixel_px.x, f.pixel_px.y});
      e["depth_m"] = json::value(f.depth_m);
      e["in_front"] = f.inFront;
      e["in_image"] = f.inImage;
      e["unoccluded"] = f.unoccluded;
      e["visible"] = f.visible();
      features.append(e);
    }
    list.append(target);
  }
  return json::write(d);
}

}  // namespace

FeatureFiles writeFeatureFiles(const std::string& dir, const std::string& stem, const PreparedScene& scene,
                               std::size_t camera, int frame) {
  const std::vector<TargetTruth> targets = targetFeatureTruth(scene, camera);
  if (targets.empty()) return {};
  warnAboutTargetViews(scene, camera, frame, targets);
  FeatureFiles files{dir + "/" + stem + ".features.csv", dir + "/" + stem + ".features.json"};
  writeTextAtomically(files.csv, csvText(targets));
  writeTextAtomically(files.json, jsonText(scene, camera, frame, targets));
  return files;
}

}  // namespace dicsynth
