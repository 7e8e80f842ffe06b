#include "io/feature_files.h"

#include <cmath>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/json.h"
#include "render/target_features.h"

namespace dicsynth {
namespace {

const char* kindName(TextureKind kind) {
  return kind == TextureKind::Checkerboard ? "checkerboard" : "circle_grid";
}

// Exact (core/exact_number.h); NaN as "nan" in CSV, whatever its sign bit.
std::string csvNumber(double v) { return std::isnan(v) ? "nan" : exactNumber(v); }

std::string jsonVector(std::initializer_list<double> values) {
  std::string out = "[";
  for (double v : values) out += (out.size() > 1 ? ", " : "") + json::number(v);
  return out + "]";
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
  std::ostringstream s;
  s << "{\n  \"scene\": " << json::quote(scene.file) << ",\n  \"camera\": " << json::quote(c.camera.name)
    << ",\n  \"frame\": " << frame << ",\n  \"image_size\": [" << c.camera.width_px << ", "
    << c.camera.height_px << "],\n  \"targets\": [";
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const TargetTruth& t = targets[i];
    const TargetLayout& l = *t.layout;
    // The target's pose in the camera, as cv::calibrateCamera / cv::solvePnP state it:
    // x_camera = R x_target + t.
    const dmat4& wt = scene.objects[t.object].worldFromTarget;
    const dmat3 R = c.rotationCameraFromWorld * dmat3(wt);
    const dvec3 tv = c.rotationCameraFromWorld * dvec3(wt[3]) + c.translationCameraFromWorld;
    s << (i ? "," : "") << "\n    {\"name\": " << json::quote(t.name) << ", \"kind\": \"" << kindName(l.kind)
      << "\", \"pattern_size\": [" << l.perRow << ", " << l.rows << "], \"asymmetric\": "
      << json::boolean(l.pattern.asymmetric) << ", \"spacing_m\": " << json::number(l.pattern.spacing_m)
      << ",\n     \"R_camera_from_target\": "
      << jsonVector({R[0][0], R[1][0], R[2][0], R[0][1], R[1][1], R[2][1], R[0][2], R[1][2], R[2][2]})
      << ",\n     \"t_camera_from_target_m\": " << jsonVector({tv.x, tv.y, tv.z}) << ",\n     \"features\": [";
    for (std::size_t k = 0; k < t.features.size(); ++k) {
      const FeatureTruth& f = t.features[k];
      s << (k ? "," : "") << "\n      {\"index\": " << f.index << ", \"row\": " << f.row << ", \"col\": " << f.col
        << ", \"target_m\": " << jsonVector({f.target_m.x, f.target_m.y, f.target_m.z})
        << ", \"world_m\": " << jsonVector({f.world_m.x, f.world_m.y, f.world_m.z})
        << ", \"pixel\": " << jsonVector({f.pixel_px.x, f.pixel_px.y}) << ", \"depth_m\": " << json::number(f.depth_m)
        << ", \"in_front\": " << json::boolean(f.inFront) << ", \"in_image\": " << json::boolean(f.inImage)
        << ", \"unoccluded\": " << json::boolean(f.unoccluded) << ", \"visible\": " << json::boolean(f.visible())
        << "}";
    }
    s << "\n     ]}";
  }
  s << "\n  ]\n}\n";
  return s.str();
}

}  // namespace

FeatureFiles writeFeatureFiles(const std::string& dir, const std::string& stem, const PreparedScene& scene,
                               std::size_t camera, int frame) {
  const std::vector<TargetTruth> targets = targetFeatureTruth(scene, camera);
  if (targets.empty()) return {};
  FeatureFiles files{dir + "/" + stem + ".features.csv", dir + "/" + stem + ".features.json"};
  writeTextAtomically(files.csv, csvText(targets));
  writeTextAtomically(files.json, jsonText(scene, camera, frame, targets));
  return files;
}

}  // namespace dicsynth
