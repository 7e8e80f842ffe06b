// Calibration files (see calibration_files.h and docs/outputs.md).
//
// OpenCV FileStorage YAML is written by hand in exactly the layout cv::FileStorage writes
// (%YAML:1.0, "!!opencv-matrix" maps with rows, cols, dt, data), so the product needs no OpenCV; the
// test suite reads every file back with cv::FileStorage.
//
// DICe camera-system XML follows DICe's Camera_System::read_camera_system_file (a Teuchos
// ParameterList): xml_file_format = DICe_xml_camera_system_file, system_type_3D = OPENCV, one
// sublist "CAMERA <i>" per camera with CX, CY, FX, FY (px), FS (skew, 0 here), K1, K2, K3, P1, P2
// (OpenCV's model: LENS_DISTORTION_MODEL = OPENCV_LENS_DISTORTION), TX, TY, TZ and a
// rotation_3x3_matrix sublist (rows "ROW 0".."ROW 2") that map DICe's world frame to the camera:
// x_cam = R·x_world + (TX, TY, TZ), and IMAGE_HEIGHT_WIDTH "{ h, w }" (height first). We write the
// left camera as CAMERA 0 with R = I, T = 0, so DICe's world frame is the left camera's frame (as
// after a calibration in DICe or OpenCV), and the right camera as CAMERA 1 with the stereo R, T.
#include "io/calibration_files.h"

#include <filesystem>
#include <memory>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/termination.h"
#include "core/version.h"
#include "io/opencv_camera.h"

namespace dicsynth {
namespace {

template <class Container>
std::string numberList(const Container& values, const char* separator) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? separator : "") + exactNumberPlainZero(values[i]);
  return text;
}

// ---- OpenCV FileStorage YAML ------------------------------------------------------------------

std::string yamlHeader(const std::string& what) {
  return "%YAML:1.0\n---\n"
         "# dicsynth " + std::string(kVersion) + ": exact calibration of " + what + ".\n"
         "# OpenCV conventions: pixel (0, 0) is the centre of the top-left pixel; distortion\n"
         "# coefficients k1 k2 p1 p2 k3 (OpenCV's order; 8 add k4 k5 k6, 12 add s1 s2 s3 s4);\n"
         "# lengths in metres.\n";
}

template <class Container>
std::string yamlMatrix(const std::string& key, int rows, int cols, const Container& data) {
  return key + ": !!opencv-matrix\n   rows: " + std::to_string(rows) + "\n   cols: " +
         std::to_string(cols) + "\n   dt: d\n   data: [ " + numberList(data, ", ") + " ]\n";
}

// A double-quoted YAML scalar. Names are global variable names, usually identifiers, but a scene may
// write _G["any text"]: quotes, backslashes, tabs and line breaks are escaped the way
// cv::FileStorage reads them back. It reads no other escape correctly (its \x yields 0, measured
// with OpenCV 4.6), so any other control character is written as '?'.
std::string yamlString(const std::string& key, const std::string& value) {
  std::string quoted;
  for (char c : value) {
    switch (c) {
      case '"': quoted += "\\\""; break;
      case '\\': quoted += "\\\\"; break;
      case '\t': quoted += "\\t"; break;
      case '\n': quoted += "\\n"; break;
      case '\r': quoted += "\\r"; break;
      default: quoted += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
    }
  }
  return key + ": \"" + quoted + "\"\n";
}

// What OpenCV's pinhole model cannot say (docs/outputs.md). ThinLens: the camera matrix is
// its chief ray's pinhole (exact for projections and the ground truth); the blur (aperture, focus)
// is extra. Orthographic: OpenCV has no telecentric camera; the matrix holds px per metre of object
// and the distortion acts on metric coordinates (cameras/orthographic.h): only dicsynth's model reads it.
std::string yamlLens(const Camera& camera, const std::string& side) {
  return std::visit(
      [&side](const auto& kind) {
        if (kind.kOpenCv) return std::string();
        std::string text = yamlString("camera_model" + side, kind.kModelName);
        for (const auto& [name, value] : kind.header()) text += name + side + ": " + exactNumberPlainZero(value) + "\n";
        return text;
      },
      camera.model);
}

// The intrinsics of one camera; `side` ("", "_left", "_right") ends every key.
std::string yamlIntrinsics(const Camera& camera, const OpenCvCamera& cv, const std::string& side) {
  return yamlString("camera_name" + side, camera.name) +
         "image_width" + side + ": " + std::to_string(camera.width_px) + "\n" +
         "image_height" + side + ": " + std::to_string(camera.height_px) + "\n" +
         yamlMatrix("camera_matrix" + side, 3, 3, cv.cameraMatrix) +
         yamlMatrix("distortion_coefficients" + side, int(cv.distortion.size()), 1, cv.distortion) +
         yamlLens(camera, side);
}

// ---- DICe XML -----------------------------------------------------------------------------------

// Text for an attribute value or a comment. Tab and line breaks as character references (a parser
// would turn them into spaces); other control characters cannot appear in XML 1.0 at all: '?'.
std::string xmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\t': out += "&#9;"; break;
      case '\n': out += "&#10;"; break;
      case '\r': out += "&#13;"; break;
      default: out += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
    }
  }
  return out;
}

std::string xmlParameter(const std::string& name, const char* type, const std::string& value) {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + xmlEscape(value) +
         "\" />\n";
}

std::string diceCamera(int index, const Camera& camera, const std::array<double, 9>& R,
                       const std::array<double, 3>& T) {
  const OpenCvCamera cv = toOpenCv(camera);
  const auto& K = cv.cameraMatrix;  // fx 0 cx / 0 fy cy / 0 0 1
  const auto& d = cv.distortion;    // k1 k2 p1 p2 k3
  std::string xml = "<ParameterList name=\"CAMERA " + std::to_string(index) + "\">\n";
  xml += xmlParameter("CAMERA_ID", "string", camera.name);
  const std::pair<const char*, double> intrinsics[] = {
      {"CX", K[2]}, {"CY", K[5]}, {"FX", K[0]}, {"FY", K[4]}, {"FS", K[1]},
      {"K1", d[0]}, {"K2", d[1]}, {"K3", d[4]}, {"P1", d[2]}, {"P2", d[3]}};
  for (const auto& [name, value] : intrinsics) xml += xmlParameter(name, "double", exactNumberPlainZero(value));
  // OpenCV's rational and thin-prism terms, under DICe's names for them.
  const char* more[] = {"K4", "K5", "K6", "S1", "S2", "S3", "S4"};
  for (std::size_t i = 5; i < d.size(); ++i) xml += xmlParameter(more[i - 5], "double", exactNumberPlainZero(d[i]));
  xml += xmlParameter("LENS_DISTORTION_MODEL", "string",
                      camera.distortion.kind != DistortionKind::None ? "OPENCV_LENS_DISTORTION"
                                                                      : "NO_LENS_DISTORTION");
  xml += xmlParameter("TX", "double", exactNumberPlainZero(T[0]));
  xml += xmlParameter("TY", "double", exactNumberPlainZero(T[1]));
  xml += xmlParameter("TZ", "double", exactNumberPlainZero(T[2]));
  xml += "<ParameterList name=\"rotation_3x3_matrix\">\n";
  for (int row = 0; row < 3; ++row) {
    const std::array<double, 3> values = {R[3 * row], R[3 * row + 1], R[3 * row + 2]};
    xml += xmlParameter("ROW " + std::to_string(row), "string", "{ " + numberList(values, ", ") + " }");
  }
  xml += "</ParameterList>\n";
  xml += xmlParameter("IMAGE_HEIGHT_WIDTH", "string",
                      "{ " + std::to_string(camera.height_px) + ", " + std::to_string(camera.width_px) + " }");
  xml += xmlParameter("PIXEL_DEPTH", "int", std::to_string(camera.bitsPerPixel));
  return xml + "</ParameterList>\n";
}

// Writes `text` to the (already created) file at `path`.
const Camera& cameraNamed(const std::vector<Camera>& cameras, const std::string& name) {
  for (const Camera& camera : cameras)
    if (camera.name == name) return camera;
  throw Error("calibration files: a rig names camera '" + name + "', which the scene lacks");
}

}  // namespace

StereoExtrinsics stereoExtrinsics(const Camera& left, const Camera& right) {
  // Columns of worldFromCamera: the camera axes and the optical centre, in world coordinates.
  const dmat3 axesLeft(left.worldFromCamera), axesRight(right.worldFromCamera);
  const dvec3 centreLeft(left.worldFromCamera[3]), centreRight(right.worldFromCamera[3]);
  // x_right = Rr (X - Cr) and X = Cl + Rlᵀ x_left give x_right = Rr Rlᵀ x_left + Rr (Cl - Cr),
  // with Rr = transpose(axesRight) (rows: the right camera's axes), Rlᵀ = axesLeft.
  const dmat3 rightFromWorld = glm::transpose(axesRight);
  const dmat3 rotation = rightFromWorld * axesLeft;
  const dvec3 translation = rightFromWorld * (centreLeft - centreRight);
  StereoExtrinsics e;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) e.R[3 * row + col] = rotation[col][row];  // GLM: m[col][row]
    e.T[row] = translation[row];
  }
  return e;
}

std::string cameraYaml(const Camera& camera) {
  const OpenCvCamera cv = toOpenCv(camera);
  return yamlHeader("this camera; pose x_cam = R x_world + t") +
         yamlIntrinsics(camera, cv, "") + yamlMatrix("R", 3, 3, cv.R) + yamlMatrix("t", 3, 1, cv.t);
}

std::string rigYaml(const std::string& rigName, const Camera& left, const Camera& right) {
  const StereoExtrinsics e = stereoExtrinsics(left, right);
  return yamlHeader("this stereo rig; x_right = R x_left + T (cv::stereoCalibrate)") +
         yamlString("rig_name", rigName) + yamlIntrinsics(left, toOpenCv(left), "_left") +
         yamlIntrinsics(right, toOpenCv(right), "_right") + yamlMatrix("R", 3, 3, e.R) +
         yamlMatrix("T", 3, 1, e.T);
}

std::string diceCameraSystemXml(const Camera& left, const Camera& right) {
  const StereoExtrinsics e = stereoExtrinsics(left, right);
  std::string xml = "<ParameterList>\n";
  // Comments name no camera: a name could hold "--", which XML forbids in a comment.
  xml += "<!-- dicsynth " + std::string(kVersion) + ": exact calibration of a stereo rig, in "
         "DICe's camera-system format -->\n";
  xml += "<!-- CAMERA 0 = the left camera (reference: DICe's world frame is this camera's frame), "
         "CAMERA 1 = the right camera; CAMERA_ID = their dicsynth names -->\n";
  xml += "<!-- pixel (0, 0) = centre of the top-left pixel; lengths in metres; CAMERA 1: "
         "x_cam1 = R x_cam0 + (TX, TY, TZ), the stereo R, T of OpenCV -->\n";
  xml += xmlParameter("xml_file_format", "string", "DICe_xml_camera_system_file");
  xml += xmlParameter("system_type_3D", "string", "OPENCV");
  xml += xmlParameter("extrinsics_relative_camera_to_camera", "bool", "false");
  xml += diceCamera(0, left, {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0});
  xml += diceCamera(1, right, e.R, e.T);
  return xml + "</ParameterList>\n";
}

std::vector<CalibrationFile> calibrationFiles(const std::vector<Camera>& cameras,
                                              const std::vector<StereoRig>& rigs,
                                              const std::string& suffix) {
  std::vector<CalibrationFile> files;
  for (const Camera& camera : cameras) files.push_back({camera.name + suffix + ".yml", cameraYaml(camera)});
  for (const StereoRig& rig : rigs) {
    const Camera& left = cameraNamed(cameras, rig.left);
    const Camera& right = cameraNamed(cameras, rig.right);
    files.push_back({rig.name + suffix + ".yml", rigYaml(rig.name, left, right)});
    files.push_back({rig.name + suffix + ".dice.xml", diceCameraSystemXml(left, right)});
  }
  return files;
}

std::vector<CalibrationFile> calibrationFiles(const PreparedScene& scene, const std::string& suffix) {
  std::vector<Camera> cameras;
  for (const PreparedCamera& camera : scene.cameras) cameras.push_back(camera.camera);
  std::vector<StereoRig> rigs;
  for (const PreparedRig& prepared : scene.rigs) {
    StereoRig rig;
    rig.name = prepared.name;
    rig.left = cameras.at(prepared.left).name;
    rig.right = cameras.at(prepared.right).name;
    rigs.push_back(std::move(rig));
  }
  return calibrationFiles(cameras, rigs, suffix);
}

std::vector<std::string> calibrationSignature(const Scene& scene) {
  std::vector<std::string> texts;
  for (const CalibrationFile& file : calibrationFiles(scene.cameras, scene.rigs, ""))
    texts.push_back(file.name + '\n' + file.text);
  return texts;
}

bool sameCalibration(const std::vector<Scene>& scenes) {
  if (scenes.empty()) return true;
  const std::vector<std::string> first = calibrationSignature(scenes.front());
  for (std::size_t i = 1; i < scenes.size(); ++i)
    if (calibrationSignature(scenes[i]) != first) return false;
  return true;
}

std::vector<std::string> writeCalibrationFiles(const std::string& dir,
                                               const std::vector<CalibrationFile>& files) {
  // Stage: every file complete under its temporary name.
  std::vector<std::unique_ptr<AtomicFile>> staged;
  for (const CalibrationFile& file : files) {
    staged.push_back(std::make_unique<AtomicFile>((std::filesystem::path(dir) / file.name).string()));
    writeText(*staged.back(), file.text);
  }
  // Commit: rename all; on a failure take back what this call renamed.
  std::vector<std::string> paths;
  const auto hold = holdTermination();  // every rename, or a signal's cleanup first
  try {
    for (auto& file : staged) {
      file->commit();
      paths.push_back(file->finalPath());
    }
  } catch (...) {
    std::error_code ignored;
    for (const std::string& path : paths) std::filesystem::remove(path, ignored);
    throw;
  }
  return paths;
}

}  // namespace dicsynth
