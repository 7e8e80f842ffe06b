// Calibration files (io/calibration_files.h), read back by the tools they are written for: OpenCV's
// cv::FileStorage for the YAML files, an XML parser for the DICe camera-system file, whose values
// are then used as DICe's model uses them; the stereo R, T checked against the two poses and against
// cv::stereoCalibrate itself.
#include <doctest/doctest.h>

#include <OpenImageIO/detail/pugixml/pugixml.hpp>  // OIIO's bundled pugixml: a test-only XML parser
// OpenCV 4.6's headers do enum arithmetic that C++20 deprecates; not ours to fix.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-enum-enum-conversion"
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#pragma GCC diagnostic pop

#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "core/error.h"
#include "io/calibration_files.h"
#include "io/opencv_camera.h"
#include "scene/stereo_rig.h"
#include "temp_folder.h"

using namespace dicsynth;
using test::TempFolder;

namespace {

Camera makeCamera(const std::string& name, int width, int height, double f, const dmat4& pose) {
  Camera c;
  c.name = name;
  c.width_px = width;
  c.height_px = height;
  c.model = cameras::Pinhole{.focalLength_m = f};
  c.pixelSize_m = {3.45e-6, 3.47e-6};
  c.principalPoint_px = {width / 2.0 - 3.3, height / 2.0 + 1.7};
  c.bitsPerPixel = 12;
  c.distortion = {DistortionKind::Brown, -0.12, 0.071, 0.013, 1.1e-4, -2.3e-4};
  c.worldFromCamera = pose;
  return c;
}

// A rig 3 m away from the world origin, turned, with two different cameras.
std::pair<Camera, Camera> makeRig() {
  StereoRigLayout layout;
  layout.centre_m = {2.1, -0.4, -1.9};
  layout.axis = {-0.5, 0.1, 1};
  layout.up = {0, -1, 0.2};
  layout.baseline_m = 0.3;
  layout.vergence_rad = 0.35;
  const StereoRigPoses poses = stereoRigPoses(layout);
  return {makeCamera("rig.left", 1600, 1200, 0.025, poses.worldFromLeft),
          makeCamera("rig.right", 1280, 1024, 0.0251, poses.worldFromRight)};
}

StereoRig rigNamed(const std::string& name) {
  StereoRig rig;
  rig.name = name;
  rig.left = name + ".left";
  rig.right = name + ".right";
  return rig;
}

std::vector<double> matValues(const cv::Mat& m) {
  cv::Mat d;
  m.convertTo(d, CV_64F);
  return std::vector<double>(d.begin<double>(), d.end<double>());
}

template <std::size_t N>
std::vector<double> values(const std::array<double, N>& a) { return {a.begin(), a.end()}; }
std::vector<double> values(const std::vector<double>& a) { return a; }

cv::Matx33d matx33(const std::array<double, 9>& a) { return cv::Matx33d(a.data()); }
cv::Vec3d vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// Projects world points through a camera with OpenCV (independent of dicsynth's camera code).
std::vector<cv::Point2d> project(const std::vector<cv::Point3d>& world, const Camera& camera) {
  const OpenCvCamera cv = toOpenCv(camera);
  cv::Vec3d rvec;
  cv::Rodrigues(matx33(cv.R), rvec);
  std::vector<cv::Point2d> image;
  cv::projectPoints(world, rvec, vec3(cv.t), matx33(cv.cameraMatrix),
                    std::vector<double>(cv.distortion.begin(), cv.distortion.end()), image);
  return image;
}

double parseDouble(const char* text) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  REQUIRE(*end == '\0');
  return value;
}

// "{ a, b, c }" → numbers, as DICe's Teuchos::fromStringToArray reads it.
std::vector<double> parseBraceList(std::string text) {
  REQUIRE(text.size() >= 2);
  REQUIRE(text.front() == '{');
  REQUIRE(text.back() == '}');
  std::vector<double> out;
  std::stringstream in(text.substr(1, text.size() - 2));
  std::string item;
  while (std::getline(in, item, ',')) {
    const std::size_t first = item.find_first_not_of(' '), last = item.find_last_not_of(' ');
    REQUIRE(first != std::string::npos);
    out.push_back(parseDouble(item.substr(first, last - first + 1).c_str()));
  }
  return out;
}

// A DICe ParameterList as name → (type, value), and its sublists by name.
struct ParameterList {
  std::map<std::string, std::pair<std::string, std::string>> parameters;
  std::map<std::string, pugi::xml_node> sublists;
};

ParameterList readList(pugi::xml_node node) {
  ParameterList list;
  for (pugi::xml_node child : node.children()) {
    const std::string tag = child.name();
    if (tag == "Parameter") {
      CHECK(list.parameters.count(child.attribute("name").value()) == 0);  // no duplicate names
      list.parameters[child.attribute("name").value()] = {child.attribute("type").value(),
                                                         child.attribute("value").value()};
    } else if (tag == "ParameterList") {
      list.sublists[child.attribute("name").value()] = child;
    } else {
      FAIL("unexpected element <" << tag << ">");
    }
  }
  return list;
}

double doubleParameter(const ParameterList& list, const std::string& name) {
  REQUIRE(list.parameters.count(name) == 1);
  CHECK(list.parameters.at(name).first == "double");
  return parseDouble(list.parameters.at(name).second.c_str());
}

}  // namespace

TEST_CASE("calibration: stereo R, T map the left camera frame to the right one") {
  const auto [left, right] = makeRig();
  const StereoExtrinsics e = stereoExtrinsics(left, right);
  const OpenCvCamera l = toOpenCv(left), r = toOpenCv(right);
  const cv::Matx33d R = matx33(e.R);
  const cv::Vec3d T = vec3(e.T);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-3, 3);
  for (int i = 0; i < 1000; ++i) {
    const cv::Vec3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    const cv::Vec3d xLeft = matx33(l.R) * x + vec3(l.t), xRight = matx33(r.R) * x + vec3(r.t);
    // Coordinates up to ~6 m through a few products and sums: rounding ~1e-15 m; 1e-12 m catches
    // any convention error (a transposed R or a sign of T is off by metres).
    CHECK(cv::norm(R * xLeft + T - xRight) < 1e-12);
  }
}

TEST_CASE("calibration: cv::stereoCalibrate recovers the written R, T from exact projections") {
  // A 9×6 grid (25 mm) in 8 poses in front of the rig, projected by OpenCV through each camera; with
  // the intrinsics fixed, stereoCalibrate's R, T must be ours: this pins the convention
  // (x_right = R·x_left + T) on OpenCV's own definition rather than on our reading of its docs.
  const auto [left, right] = makeRig();
  const OpenCvCamera l = toOpenCv(left), r = toOpenCv(right);
  std::vector<cv::Point3f> grid;
  for (int row = 0; row < 6; ++row)
    for (int col = 0; col < 9; ++col) grid.emplace_back(0.025f * (col - 4), 0.025f * (row - 2.5f), 0.f);
  // Target poses: in the left camera's frame, 0.8 m ahead where the axes nearly cross, tilted.
  std::vector<std::vector<cv::Point3f>> objectPoints;
  std::vector<std::vector<cv::Point2f>> imageLeft, imageRight;
  const dmat4 worldFromLeft = left.worldFromCamera;
  for (int view = 0; view < 8; ++view) {
    const cv::Vec3d rvec(0.3 * std::sin(view), 0.25 * std::cos(1.7 * view), 0.2 * view - 0.7);
    cv::Matx33d rotation;
    cv::Rodrigues(rvec, rotation);
    const cv::Vec3d offset(0.02 * std::cos(view), 0.015 * std::sin(2 * view), 0.85 + 0.03 * view);
    std::vector<cv::Point3d> world;
    for (const cv::Point3f& p : grid) {
      const cv::Vec3d inLeft = rotation * cv::Vec3d(p.x, p.y, p.z) + offset;
      const dvec4 w = worldFromLeft * dvec4(inLeft[0], inLeft[1], inLeft[2], 1);
      world.emplace_back(w.x, w.y, w.z);
    }
    std::vector<cv::Point2f> pl, pr;
    for (const cv::Point2d& q : project(world, left)) pl.emplace_back(float(q.x), float(q.y));
    for (const cv::Point2d& q : project(world, right)) pr.emplace_back(float(q.x), float(q.y));
    objectPoints.push_back(grid);
    imageLeft.push_back(pl);
    imageRight.push_back(pr);
  }
  cv::Mat K1(3, 3, CV_64F, const_cast<double*>(l.cameraMatrix.data()));
  cv::Mat K2(3, 3, CV_64F, const_cast<double*>(r.cameraMatrix.data()));
  cv::Mat D1(1, 5, CV_64F, const_cast<double*>(l.distortion.data()));
  cv::Mat D2(1, 5, CV_64F, const_cast<double*>(r.distortion.data()));
  cv::Mat R, T, E, F;
  const double rms = cv::stereoCalibrate(
      objectPoints, imageLeft, imageRight, K1, D1, K2, D2, cv::Size(left.width_px, left.height_px), R, T,
      E, F, cv::CALIB_FIX_INTRINSIC, cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-15));
  const StereoExtrinsics e = stereoExtrinsics(left, right);
  // The image points were rounded to float (OpenCV's point type here), ~3e-5 px at 1600 px: that
  // noise alone limits the fit (measured: RMS 3.0e-5 px, R and T within 6e-9). 1e-6 (unitless, m)
  // leaves a wide margin yet is far below any convention error (of the order of the baseline or
  // the vergence: 0.3 m, 0.35 rad).
  CHECK(rms < 1e-4);
  const std::vector<double> gotR = matValues(R), gotT = matValues(T);
  for (int k = 0; k < 9; ++k) CHECK(gotR[k] == doctest::Approx(e.R[k]).scale(1).epsilon(1e-6));
  for (int k = 0; k < 3; ++k) CHECK(gotT[k] == doctest::Approx(e.T[k]).scale(1).epsilon(1e-6));
}

TEST_CASE("calibration: the YAML files read back with cv::FileStorage, every double exact") {
  TempFolder dir;
  const auto [left, right] = makeRig();
  const std::vector<std::string> paths =
      writeCalibrationFiles(dir.path().string(), calibrationFiles({left, right}, {rigNamed("rig")}, ""));
  CHECK(paths.size() == 4);
  CHECK(dir.entries() == std::vector<std::string>{"rig.dice.xml", "rig.left.yml", "rig.right.yml", "rig.yml"});

  for (const Camera* camera : {&left, &right}) {
    CAPTURE(camera->name);
    cv::FileStorage fs(dir.file(camera->name + ".yml"), cv::FileStorage::READ);
    REQUIRE(fs.isOpened());
    const OpenCvCamera cv = toOpenCv(*camera);
    CHECK(std::string(fs["camera_name"]) == camera->name);
    CHECK(int(fs["image_width"]) == camera->width_px);
    CHECK(int(fs["image_height"]) == camera->height_px);
    cv::Mat K, D, R, t;
    fs["camera_matrix"] >> K;
    fs["distortion_coefficients"] >> D;
    fs["R"] >> R;
    fs["t"] >> t;
    CHECK(K.type() == CV_64F);
    CHECK(K.size() == cv::Size(3, 3));
    CHECK(D.size() == cv::Size(1, 5));  // 5 rows, 1 column, as calibrateCamera's sample writes it
    CHECK(R.size() == cv::Size(3, 3));
    CHECK(t.size() == cv::Size(1, 3));
    CHECK(matValues(K) == values(cv.cameraMatrix));  // exact: %.17g round-trips every double
    CHECK(matValues(D) == values(cv.distortion));
    CHECK(matValues(R) == values(cv.R));
    CHECK(matValues(t) == values(cv.t));
  }

  // A scene may name a global _G["any text"]: such a name reads back as it was.
  Camera odd = left;
  odd.name = "a \"quoted\" \\ name\twith\ncontrol characters";
  writeCalibrationFiles(dir.path().string(), {{"odd.yml", cameraYaml(odd)}});
  CHECK(std::string(cv::FileStorage(dir.file("odd.yml"), cv::FileStorage::READ)["camera_name"]) == odd.name);

  cv::FileStorage fs(dir.file("rig.yml"), cv::FileStorage::READ);
  REQUIRE(fs.isOpened());
  const StereoExtrinsics e = stereoExtrinsics(left, right);
  CHECK(std::string(fs["rig_name"]) == "rig");
  CHECK(std::string(fs["camera_name_left"]) == "rig.left");
  CHECK(std::string(fs["camera_name_right"]) == "rig.right");
  CHECK(int(fs["image_width_left"]) == 1600);
  CHECK(int(fs["image_height_right"]) == 1024);
  cv::Mat K1, D1, K2, D2, R, T;
  fs["camera_matrix_left"] >> K1;
  fs["distortion_coefficients_left"] >> D1;
  fs["camera_matrix_right"] >> K2;
  fs["distortion_coefficients_right"] >> D2;
  fs["R"] >> R;
  fs["T"] >> T;
  CHECK(matValues(K1) == values(toOpenCv(left).cameraMatrix));
  CHECK(matValues(D1) == values(toOpenCv(left).distortion));
  CHECK(matValues(K2) == values(toOpenCv(right).cameraMatrix));
  CHECK(matValues(D2) == values(toOpenCv(right).distortion));
  CHECK(T.size() == cv::Size(1, 3));
  CHECK(matValues(R) == values(e.R));
  CHECK(matValues(T) == values(e.T));
}

TEST_CASE("calibration: the DICe camera-system XML parses and projects as the right camera does") {
  const auto [left, right] = makeRig();
  const std::string xml = diceCameraSystemXml(left, right);
  pugi::xml_document document;
  const pugi::xml_parse_result parsed = document.load_string(xml.c_str());
  INFO(xml);
  REQUIRE(parsed);  // well-formed XML
  REQUIRE(std::distance(document.children().begin(), document.children().end()) == 1);
  const pugi::xml_node root = document.first_child();
  REQUIRE(std::string(root.name()) == "ParameterList");
  const ParameterList system = readList(root);
  CHECK(system.parameters.at("xml_file_format") == std::pair<std::string, std::string>("string", "DICe_xml_camera_system_file"));
  CHECK(system.parameters.at("system_type_3D") == std::pair<std::string, std::string>("string", "OPENCV"));
  CHECK(system.parameters.at("extrinsics_relative_camera_to_camera") == std::pair<std::string, std::string>("bool", "false"));
  REQUIRE(system.sublists.size() == 2);

  const StereoExtrinsics e = stereoExtrinsics(left, right);
  for (int index = 0; index < 2; ++index) {
    const Camera& camera = index == 0 ? left : right;
    CAPTURE(index);
    REQUIRE(system.sublists.count("CAMERA " + std::to_string(index)) == 1);
    const ParameterList list = readList(system.sublists.at("CAMERA " + std::to_string(index)));
    const OpenCvCamera cv = toOpenCv(camera);
    CHECK(list.parameters.at("CAMERA_ID").second == camera.name);
    CHECK(list.parameters.at("LENS_DISTORTION_MODEL").second == "OPENCV_LENS_DISTORTION");
    CHECK(list.parameters.at("PIXEL_DEPTH") == std::pair<std::string, std::string>("int", "12"));
    CHECK(parseBraceList(list.parameters.at("IMAGE_HEIGHT_WIDTH").second) ==
          std::vector<double>{double(camera.height_px), double(camera.width_px)});
    const double fx = doubleParameter(list, "FX"), fy = doubleParameter(list, "FY");
    const double cx = doubleParameter(list, "CX"), cy = doubleParameter(list, "CY");
    const double k1 = doubleParameter(list, "K1"), k2 = doubleParameter(list, "K2"), k3 = doubleParameter(list, "K3");
    const double p1 = doubleParameter(list, "P1"), p2 = doubleParameter(list, "P2");
    CHECK(doubleParameter(list, "FS") == 0);
    CHECK(std::vector<double>{fx, 0, cx, 0, fy, cy, 0, 0, 1} == values(cv.cameraMatrix));
    CHECK(std::vector<double>{k1, k2, p1, p2, k3} == values(cv.distortion));
    REQUIRE(list.sublists.count("rotation_3x3_matrix") == 1);
    const ParameterList rotation = readList(list.sublists.at("rotation_3x3_matrix"));
    std::array<double, 9> R{};
    for (int row = 0; row < 3; ++row) {
      const auto& [type, text] = rotation.parameters.at("ROW " + std::to_string(row));
      CHECK(type == "string");
      const std::vector<double> numbers = parseBraceList(text);
      REQUIRE(numbers.size() == 3);
      for (int col = 0; col < 3; ++col) R[3 * row + col] = numbers[col];
    }
    const std::array<double, 3> T = {doubleParameter(list, "TX"), doubleParameter(list, "TY"), doubleParameter(list, "TZ")};
    if (index == 0) {  // the reference: DICe's world frame is the left camera's frame
      CHECK(R == std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1});
      CHECK(T == std::array<double, 3>{0, 0, 0});
    } else {
      CHECK(R == e.R);
      CHECK(T == e.T);
    }

    // DICe's OPENCV_LENS_DISTORTION model (Camera::sensor_to_image) with these values, applied to
    // world points taken into DICe's world frame (the left camera's), must give OpenCV's projection
    // through the camera's own pose: 1e-9 px is far above rounding (~1e-12 px at 1600 px) and far
    // below any swapped coefficient or transposed rotation.
    const OpenCvCamera l = toOpenCv(left);
    std::mt19937_64 rng(11 + index);
    std::uniform_real_distribution<double> spread(-0.1, 0.1);
    std::vector<cv::Point3d> world;
    std::vector<cv::Point2d> dice;
    for (int i = 0; i < 50; ++i) {
      // Points around the crossing of the optical axes, 0.5 m ahead of the left camera.
      const cv::Vec3d inLeft(spread(rng), spread(rng), 0.5 + spread(rng));
      const dvec4 w = left.worldFromCamera * dvec4(inLeft[0], inLeft[1], inLeft[2], 1);
      world.emplace_back(w.x, w.y, w.z);
      const cv::Vec3d diceWorld = matx33(l.R) * cv::Vec3d(w.x, w.y, w.z) + vec3(l.t);
      const cv::Vec3d c = matx33(R) * diceWorld + vec3(T);
      const double x = c[0] / c[2], y = c[1] / c[2], r2 = x * x + y * y;
      const double radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2;
      const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
      const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
      dice.emplace_back(xd * fx + cx, yd * fy + cy);
    }
    const std::vector<cv::Point2d> expected = project(world, camera);
    for (std::size_t i = 0; i < world.size(); ++i) CHECK(cv::norm(dice[i] - expected[i]) < 1e-9);
  }
}

TEST_CASE("calibration: DICe XML without distortion says NO_LENS_DISTORTION, odd names read back") {
  auto [left, right] = makeRig();
  left.distortion = {};
  // A scene may name a global _G["any text"]: the XML stays well-formed and keeps the name.
  left.name = "<a> & \"b\" -- c\td\ne";
  const std::string xml = diceCameraSystemXml(left, right);
  pugi::xml_document document;
  REQUIRE(document.load_string(xml.c_str()));
  const ParameterList system = readList(document.first_child());
  CHECK(readList(system.sublists.at("CAMERA 0")).parameters.at("LENS_DISTORTION_MODEL").second == "NO_LENS_DISTORTION");
  CHECK(readList(system.sublists.at("CAMERA 0")).parameters.at("CAMERA_ID").second == left.name);
  CHECK(readList(system.sublists.at("CAMERA 1")).parameters.at("LENS_DISTORTION_MODEL").second == "OPENCV_LENS_DISTORTION");
}

TEST_CASE("calibration: same cameras in every frame give one unnumbered set, any change one per frame") {
  const auto [left, right] = makeRig();
  Scene a;
  a.cameras = {left, right};
  a.rigs = {rigNamed("rig")};
  Scene b = a;
  CHECK(sameCalibration({a, b, a}));
  b.cameras[1].worldFromCamera[3].x += 1e-15;  // the smallest pose change still changes the files
  CHECK_FALSE(sameCalibration({a, b}));
  b = a;
  b.cameras[0].distortion.k3 = 0.1;
  CHECK_FALSE(sameCalibration({a, b}));
  b = a;
  b.rigs.clear();
  CHECK_FALSE(sameCalibration({a, b}));
  CHECK(sameCalibration({a}));

  const std::vector<CalibrationFile> files = calibrationFiles(a.cameras, a.rigs, "_0007");
  std::vector<std::string> names;
  for (const CalibrationFile& f : files) names.push_back(f.name);
  CHECK(names == std::vector<std::string>{"rig.left_0007.yml", "rig.right_0007.yml", "rig_0007.yml", "rig_0007.dice.xml"});
  CHECK_THROWS_AS(calibrationFiles({left}, a.rigs, ""), Error);  // a rig naming a missing camera: a bug
}

TEST_CASE("calibration: a failed write leaves none of the files behind") {
  TempFolder dir;
  // A folder where the second file goes: its rename fails after the first file was renamed.
  std::filesystem::create_directories(dir.file("b.yml/inside"));
  const std::vector<CalibrationFile> files = {{"a.yml", "a"}, {"b.yml", "b"}, {"c.yml", "c"}};
  CHECK_THROWS_AS(writeCalibrationFiles(dir.path().string(), files), Error);
  CHECK(dir.entries() == std::vector<std::string>{"b.yml"});  // no a.yml, no c.yml, no temporary
  // A missing folder: an Error naming it, nothing created.
  CHECK_THROWS_WITH_AS(writeCalibrationFiles(dir.file("missing"), files),
                       doctest::Contains("missing"), Error);
  CHECK_FALSE(std::filesystem::exists(dir.file("missing")));
}

TEST_CASE("calibration: a zero is written 0, never -0 (a camera at the origin)") {
  // The audit of 2026-11-27 read `t: [ -0, -0, -0 ]` in the .yml of a camera at the world origin
  // (t = -R C with C = 0) and -0 entries in R. The same value for every reader, but not what a user
  // expects to read; the fix writes +0.
  dmat4 pose(1.0);
  pose[1][1] = -1.0;  // looking along +z with y down: R = diag(1, -1, -1) and zeros
  pose[2][2] = -1.0;
  const Camera left = makeCamera("origin.left", 64, 48, 0.012, pose);
  const Camera right = makeCamera("origin.right", 64, 48, 0.012, pose);  // the same place: R = I, T = 0
  const std::regex negativeZero(R"((^|[^0-9.eE])-0($|[^0-9.]))");
  for (const std::string& text : {cameraYaml(left), rigYaml("origin", left, right), diceCameraSystemXml(left, right)}) {
    CAPTURE(text);
    CHECK(!std::regex_search(text, negativeZero));
  }
  // The check can fail: it finds a -0 where there is one.
  CHECK(std::regex_search(std::string("t: [ 0, -0, 0 ]"), negativeZero));
  CHECK(!std::regex_search(std::string("t: [ -0.5, 1e-05, -0.25 ]"), negativeZero));
}
