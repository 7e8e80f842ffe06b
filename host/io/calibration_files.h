#pragma once
// Calibration ground truth in the formats calibration and DIC tools read (docs/outputs.md, "Calibration
// files"). All numbers have 17 significant digits, so every double reads back exactly.
//
//   DIR/<camera>.yml      OpenCV FileStorage YAML: image size, camera matrix, distortion, pose R, t
//   DIR/<rig>.yml         OpenCV FileStorage YAML: both cameras' intrinsics and the stereo R, T
//   DIR/<rig>.dice.xml    DICe camera-system file (xml_file_format DICe_xml_camera_system_file)
//
// Conventions (docs/design.md §3): pixel coordinates as OpenCV (centre of the top-left pixel = (0, 0)),
// distortion coefficients in OpenCV's order k1 k2 p1 p2 k3, pose x_cam = R·x_world + t, stereo
// relation x_right = R·x_left + T as cv::stereoCalibrate returns it; lengths in metres.
#include <array>
#include <string>
#include <vector>

#include "geometry/prepared_scene.h"
#include "model/scene.h"

namespace dicsynth {

// A file's name in the output folder and its complete contents.
struct CalibrationFile {
  std::string name;
  std::string text;
};

// The relation of two cameras as cv::stereoCalibrate returns it: x_right = R·x_left + T, with x_left,
// x_right in the cameras' (OpenCV) frames. R row-major; T in metres (the left optical centre seen
// from the right camera). Computed from the poses' axes and the difference of the optical centres,
// so its rounding error scales with the baseline, not with the rig's distance from the origin.
struct StereoExtrinsics {
  std::array<double, 9> R{};
  std::array<double, 3> T{};
};
StereoExtrinsics stereoExtrinsics(const Camera& left, const Camera& right);

// The three formats, for one camera or one rig (left = DICe's CAMERA 0).
std::string cameraYaml(const Camera& camera);
std::string rigYaml(const std::string& rigName, const Camera& left, const Camera& right);
std::string diceCameraSystemXml(const Camera& left, const Camera& right);

// Every calibration file of `cameras` and `rigs` (rigs name their cameras; each must be among
// `cameras`, else Error). `suffix` goes between the name and the extension: "" or "_0003".
std::vector<CalibrationFile> calibrationFiles(const std::vector<Camera>& cameras,
                                              const std::vector<StereoRig>& rigs,
                                              const std::string& suffix);
std::vector<CalibrationFile> calibrationFiles(const PreparedScene& scene, const std::string& suffix);

// True when all scenes (frames) give the same calibration files: same cameras, rigs, image sizes,
// intrinsics, distortion and poses, compared exactly. Then a run writes them once, unnumbered.
bool sameCalibration(const std::vector<Scene>& scenes);
// The calibration files' names and texts of one scene: equal for two scenes exactly when their
// calibrations are (what sameCalibration compares, for callers that hold one scene at a time).
std::vector<std::string> calibrationSignature(const Scene& scene);

// Writes the files into `dir` (which must exist) and returns their paths. All of them are written
// to temporary files first and renamed only once all are complete; should a rename fail, the files
// this call renamed before are removed again, so a failure leaves none of them behind. Throws Error.
std::vector<std::string> writeCalibrationFiles(const std::string& dir,
                                               const std::vector<CalibrationFile>& files);

}  // namespace dicsynth
