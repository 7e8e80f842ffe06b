// host/io/outputs + opencv_camera: one camera's TIFF + EXR pair, read back through OpenImageIO.
#include <OpenImageIO/imageio.h>
#include <doctest/doctest.h>

#include <sys/resource.h>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "io/opencv_camera.h"
#include "exr_test_util.h"
#include "io/outputs.h"
#include "io/zip_deflate.h"
#include "temp_folder.h"

using namespace dicsynth;
using dicsynth::test::ExrContents;
using dicsynth::test::readExr;
using dicsynth::test::TempFolder;

namespace {

doctest::Contains containsText(const std::string& text) { return doctest::Contains(text.c_str()); }

const double kNaN = std::numeric_limits<double>::quiet_NaN();

Camera testCamera() {
  Camera camera;
  camera.name = "camera1";
  camera.width_px = 7;
  camera.height_px = 5;
  camera.principalPoint_px = {3.1, 1.9};
  camera.model = cameras::Pinhole{.focalLength_m = 0.035};
  camera.pixelSize_m = {3.45e-6, 3.3e-6};  // non-square: fx != fy
  camera.fillFactor = 0.7;
  camera.bitsPerPixel = 10;
  camera.exposure = 1.3;
  camera.distortion.kind = DistortionKind::Brown;
  camera.distortion.k1 = -0.11;
  camera.distortion.k2 = 0.027;
  camera.distortion.k3 = -3e-5;
  camera.distortion.p1 = 0.0013;
  camera.distortion.p2 = 2e-4;
  // A pose with every rotation axis involved and an irrational-looking translation.
  dmat4 pose = glm::translate(dmat4(1.0), dvec3(0.123, -0.456, -0.789));
  pose = glm::rotate(pose, 0.3, glm::normalize(dvec3(0.2, 1.0, -0.4)));
  pose = glm::rotate(pose, -1.1, dvec3(1, 0, 0));
  camera.worldFromCamera = pose;
  return camera;
}

// Ground truth with distinct values per pixel and channel; every third pixel is background.
CameraImage testImage(const Camera& camera) {
  CameraImage image;
  image.cameraName = camera.name;
  image.resize(camera.width_px, camera.height_px);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    image.radiance[i] = 0.01 * double(i) + 0.001;  // background has radiance too
    if (i % 3 == 0) continue;                      // background: NaN geometry, id 0
    const double k = double(i);
    image.depth_m[i] = 1.5 + 0.01 * k;
    image.position_m[i] = {0.1 * k, -0.2 * k, 1.0 + k};
    image.normal[i] = glm::normalize(dvec3(0.3, -0.4 + 0.01 * k, -1.0));
    image.uv[i] = {k / 40.0, 1.0 - k / 40.0};
    // Ids above 2^24 are not exact in float: they prove the channel is a true uint32.
    image.objectId[i] = i % 3 == 1 ? std::uint32_t(i) : std::uint32_t(16777217u + i);
  }
  return image;
}

OutputInfo testInfo() {
  OutputInfo info;
  info.sceneFile = "scenes/figure1.lua";
  info.frame = 7;
  info.seed = 4000000000u;
  info.samplesPerPixel = 16;
  info.backend = "cpu";
  info.precision = "fp64";
  info.device = "CPU reference (2 threads)";
  info.objectNames = {"plate", "sphere", "triangle"};
  return info;
}

std::vector<double> parseNumbers(const std::string& text) {
  std::vector<double> numbers;
  const char* p = text.c_str();
  char* end = nullptr;
  for (double v = std::strtod(p, &end); end != p; v = std::strtod(p, &end)) {
    numbers.push_back(v);
    p = end;
  }
  return numbers;
}

}  // namespace

TEST_CASE("io: writeCameraOutputs writes the TIFF of digital numbers with its description") {
  TempFolder folder;
  const Camera camera = testCamera();
  const CameraImage image = testImage(camera);
  std::vector<std::uint16_t> digital(image.pixelCount());
  for (std::size_t i = 0; i < digital.size(); ++i) digital[i] = std::uint16_t((i * 97) % 1024);

  const OutputFiles files = writeCameraOutputs(folder.path().string(), "camera1_0007", camera, image,
                                               digital, testInfo());
  CHECK(files.image == folder.file("camera1_0007.tif"));
  CHECK(files.groundTruth == folder.file("camera1_0007.exr"));
  CHECK(folder.entries() == std::vector<std::string>{"camera1_0007.exr", "camera1_0007.tif"});

  auto in = OIIO::ImageInput::open(files.image);
  REQUIRE(in);
  CHECK(in->spec().format == OIIO::TypeDesc::UINT16);
  std::vector<std::uint16_t> back(digital.size());
  REQUIRE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, back.data()));
  CHECK(back == digital);
  const std::string description = in->spec().get_string_attribute("ImageDescription");
  CHECK(description.find("dicsynth: raw 10-bit digital numbers in a 16-bit container; camera camera1; "
                         "frame 7") == 0);
}

TEST_CASE("io: ground-truth EXR round trip: channels, formats, values, NaN background") {
  TempFolder folder;
  const Camera camera = testCamera();
  const CameraImage image = testImage(camera);
  const std::vector<std::uint16_t> digital(image.pixelCount(), 5);
  const std::uint64_t deflated = zipDeflateCalls();
  const OutputFiles files =
      writeCameraOutputs(folder.path().string(), "c", camera, image, digital, testInfo());
  // OpenEXR's zip block went through this binary's compress2, libdeflate's (io/zip_deflate.h);
  // what it reads back below, decoded by zlib, is what was written.
  CHECK(zipDeflateCalls() > deflated);

  const ExrContents exr = readExr(files.groundTruth);
  CHECK(exr.spec.width == camera.width_px);
  CHECK(exr.spec.height == camera.height_px);
  CHECK(exr.spec.get_string_attribute("compression") == "zip");

  // Every channel, each once, with its format (the file's order is OpenEXR's, by name).
  std::map<std::string, std::string> formats;
  for (int c = 0; c < exr.spec.nchannels; ++c)
    formats[exr.spec.channelnames[c]] = exr.spec.channelformat(c).c_str();
  const std::map<std::string, std::string> expected{
      {"Y", "float"},   {"Z", "float"},   {"P.X", "float"},  {"P.Y", "float"},
      {"P.Z", "float"}, {"N.X", "float"}, {"N.Y", "float"},  {"N.Z", "float"},
      {"uv.U", "float"}, {"uv.V", "float"}, {"objectId", "uint"}, {"mask", "float"}};
  CHECK(formats == expected);
  CHECK(exr.spec.nchannels == 12);

  auto same = [](float stored, double truth) {
    return std::isnan(truth) ? std::isnan(stored) : stored == float(truth);
  };
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    CAPTURE(i);
    CHECK(exr.floats.at("Y")[i] == float(image.radiance[i]));
    CHECK(same(exr.floats.at("Z")[i], image.depth_m[i]));
    CHECK(same(exr.floats.at("P.X")[i], image.position_m[i].x));
    CHECK(same(exr.floats.at("P.Y")[i], image.position_m[i].y));
    CHECK(same(exr.floats.at("P.Z")[i], image.position_m[i].z));
    CHECK(same(exr.floats.at("N.X")[i], image.normal[i].x));
    CHECK(same(exr.floats.at("N.Y")[i], image.normal[i].y));
    CHECK(same(exr.floats.at("N.Z")[i], image.normal[i].z));
    CHECK(same(exr.floats.at("uv.U")[i], image.uv[i].x));
    CHECK(same(exr.floats.at("uv.V")[i], image.uv[i].y));
    CHECK(exr.objectId[i] == image.objectId[i]);
    CHECK(exr.floats.at("mask")[i] == (image.objectId[i] > 0 ? 1.0f : 0.0f));
    if (i % 3 == 0) CHECK(std::isnan(exr.floats.at("P.Y")[i]));  // the background really is NaN
  }
  CHECK(exr.objectId[2] == 16777217u + 2u);  // > 2^24: not through float
}

TEST_CASE("io: ground-truth EXR metadata parses back to the exact values") {
  TempFolder folder;
  const Camera camera = testCamera();
  const CameraImage image = testImage(camera);
  const OutputInfo info = testInfo();
  const OutputFiles files = writeCameraOutputs(folder.path().string(), "c", camera, image,
                                               std::vector<std::uint16_t>(image.pixelCount(), 0), info);
  const OIIO::ImageSpec spec = readExr(files.groundTruth).spec;
  auto text = [&](const char* name) {
    const OIIO::ParamValue* p = spec.find_attribute(name);
    REQUIRE_MESSAGE(p, name);
    REQUIRE(p->type() == OIIO::TypeString);
    return spec.get_string_attribute(name);
  };
  CHECK(text("dicsynth:version") == "0.1.0");
  CHECK(text("dicsynth:scene") == info.sceneFile);
  CHECK(text("dicsynth:frame") == "7");
  CHECK(text("dicsynth:seed") == "4000000000");
  CHECK(text("dicsynth:spp") == "16");
  CHECK(text("dicsynth:backend") == "cpu");
  CHECK(text("dicsynth:precision") == "fp64");
  CHECK(text("dicsynth:device") == info.device);
  CHECK(text("dicsynth:camera") == "camera1");
  CHECK(text("dicsynth:objects") == "plate,sphere,triangle");
  CHECK(text("dicsynth:image_size") == "7 5");
  CHECK(text("dicsynth:bits_per_pixel") == "10");
  CHECK(parseNumbers(text("dicsynth:exposure")) == std::vector<double>{1.3});
  CHECK(parseNumbers(text("dicsynth:fill_factor")) == std::vector<double>{0.7});
  CHECK(spec.find_attribute("DateTime") == nullptr);

  // Camera matrix and distortion: exact doubles (17 significant digits round-trip).
  const double fx = camera.focalScale() / camera.pixelSize_m.x;
  const double fy = camera.focalScale() / camera.pixelSize_m.y;
  CHECK(parseNumbers(text("dicsynth:camera_matrix")) ==
        std::vector<double>{fx, 0, 3.1, 0, fy, 1.9, 0, 0, 1});
  CHECK(parseNumbers(text("dicsynth:distortion_coefficients")) ==
        std::vector<double>{-0.11, 0.027, 0.0013, 2e-4, -3e-5});  // k1 k2 p1 p2 k3

  // R, t parse back to exactly what toOpenCv computes, and are the inverse of worldFromCamera.
  const std::vector<double> R = parseNumbers(text("dicsynth:R"));
  const std::vector<double> t = parseNumbers(text("dicsynth:t"));
  const OpenCvCamera cv = toOpenCv(camera);
  CHECK(R == std::vector<double>(cv.R.begin(), cv.R.end()));
  CHECK(t == std::vector<double>(cv.t.begin(), cv.t.end()));
  REQUIRE(R.size() == 9);
  REQUIRE(t.size() == 3);
  for (const dvec3 pCamera : {dvec3(0, 0, 0), dvec3(0.3, -0.2, 2.0), dvec3(-1, 4, 0.5)}) {
    const dvec3 pWorld = dvec3(camera.worldFromCamera * dvec4(pCamera, 1.0));
    for (int row = 0; row < 3; ++row) {
      const double back = R[3 * row] * pWorld.x + R[3 * row + 1] * pWorld.y + R[3 * row + 2] * pWorld.z + t[row];
      CHECK(back == doctest::Approx(pCamera[row]).epsilon(1e-14));
    }
  }
  double orthogonality = 0;  // R Rᵀ = I
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += R[3 * a + k] * R[3 * b + k];
      orthogonality = std::max(orthogonality, std::abs(dot - (a == b ? 1.0 : 0.0)));
    }
  CHECK(orthogonality < 1e-15);

  // OpenEXR's worldToCamera (Imath row vectors, y up): p_world · M = (x, -y, z) of OpenCV's camera.
  const OIIO::ParamValue* w2c = spec.find_attribute("worldToCamera");
  REQUIRE(w2c);
  REQUIRE(w2c->type() == OIIO::TypeMatrix);
  const float* m = static_cast<const float*>(w2c->data());
  const dvec3 pCamera(0.3, -0.2, 2.0);
  const dvec3 pWorld = dvec3(camera.worldFromCamera * dvec4(pCamera, 1.0));
  for (int col = 0; col < 3; ++col) {
    const double v = pWorld.x * m[col] + pWorld.y * m[4 + col] + pWorld.z * m[8 + col] + m[12 + col];
    CHECK(v == doctest::Approx(col == 1 ? -pCamera.y : pCamera[col]).epsilon(1e-6));
  }
  CHECK(spec.get_float_attribute("PixelAspectRatio") == doctest::Approx(3.45 / 3.3).epsilon(1e-7));
}

TEST_CASE("io: writeCameraOutputs into a missing folder throws Error naming it and creates nothing") {
  TempFolder folder;
  const Camera camera = testCamera();
  const CameraImage image = testImage(camera);
  const std::string missing = folder.file("not_there");
  CHECK_THROWS_WITH_AS(writeCameraOutputs(missing, "c", camera, image,
                                          std::vector<std::uint16_t>(image.pixelCount(), 0), testInfo()),
                       containsText(missing), Error);
  CHECK(folder.entries().empty());
}

TEST_CASE("io: when the EXR cannot be committed the TIFF is removed again") {
  // A folder in the EXR's place makes its rename fail after the TIFF was renamed.
  TempFolder folder;
  std::filesystem::create_directory(folder.path() / "c.exr");
  test::writeBytes(folder.file("c.exr/keep"), "x");
  const Camera camera = testCamera();
  const CameraImage image = testImage(camera);
  CHECK_THROWS_WITH_AS(writeCameraOutputs(folder.path().string(), "c", camera, image,
                                          std::vector<std::uint16_t>(image.pixelCount(), 0), testInfo()),
                       containsText(folder.file("c.exr")), Error);
  CHECK(folder.entries() == std::vector<std::string>{"c.exr"});  // no TIFF, no temporary file
}

namespace {

// Writes past `bytes` fail while it is set (RLIMIT_FSIZE: EFBIG, its SIGXFSZ ignored): a disk that
// fills up in the middle of a file, for the one thread or the other.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &saved_) == 0);
    previous_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &limit) == 0);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_)(int) = SIG_DFL;
};

}  // namespace

TEST_CASE("io: a write failing in either file, written side by side, leaves neither") {
  // The TIFF is written on its own thread beside the EXR (writeCameraOutputs). Whichever fails, the
  // call throws naming that file, after the other has finished, and the folder keeps no file and no
  // temporary. Each case: the sizes measured once without a limit, then a limit between them.
  Camera camera = testCamera();
  camera.width_px = 160;
  camera.height_px = 120;
  camera.principalPoint_px = {80.2, 59.7};
  const CameraImage image = testImage(camera);
  const std::size_t n = image.pixelCount();
  std::vector<std::uint16_t> flat(n, 0), noisy(n);
  std::uint32_t state = 12345;  // a linear congruential sequence: incompressible enough for deflate
  for (std::uint16_t& v : noisy) v = std::uint16_t(((state = state * 1664525u + 1013904223u) >> 16) % 1024);
  struct Case {
    const char* what;
    const std::vector<std::uint16_t>* digital;
    const char* layers;
    const char* failing;  // the larger file, which the limit cuts
  };
  const Case cases[] = {{"the EXR fails, the TIFF completes", &flat, "all", ".exr"},
                        {"the TIFF fails, the EXR completes", &noisy, "image,mask", ".tif"}};
  for (const Case& c : cases) {
    CAPTURE(c.what);
    OutputInfo info = testInfo();
    info.layers = LayerSet::parse(c.layers);
    TempFolder measured;
    const OutputFiles files = writeCameraOutputs(measured.path().string(), "c", camera, image, *c.digital, info);
    const auto tif = std::filesystem::file_size(files.image), exr = std::filesystem::file_size(files.groundTruth);
    const bool exrLarger = std::string(c.failing) == ".exr";
    REQUIRE((exrLarger ? exr > 2 * tif : tif > 2 * exr));  // the limit below falls clearly between
    TempFolder folder;
    const std::string failing = folder.file(std::string("c") + c.failing);
    // Only the call runs under the limit (the test's own report may go to a file).
    bool thrown = false;
    std::string message;
    {
      const FileSizeLimit limit((tif + exr) / 2);
      try {
        writeCameraOutputs(folder.path().string(), "c", camera, image, *c.digital, info);
      } catch (const Error& e) {
        thrown = true;
        message = e.what();
      }
    }
    CHECK(thrown);
    CHECK_MESSAGE(message.find(failing) != std::string::npos, message);
    CHECK(folder.entries().empty());
  }
}

TEST_CASE("io: cameraFromWorld rejects a non-rigid pose") {
  Camera camera = testCamera();
  camera.worldFromCamera = glm::scale(camera.worldFromCamera, dvec3(1.0, 1.0, 1.001));
  CHECK_THROWS_AS(cameraFromWorld(camera), Error);
  camera.worldFromCamera = glm::scale(dmat4(1.0), dvec3(1.0, -1.0, 1.0));  // a mirror
  CHECK_THROWS_AS(cameraFromWorld(camera), Error);
  Camera plain;
  plain.worldFromCamera = glm::translate(dmat4(1.0), dvec3(1, 2, 3));
  const OpenCvCamera cv = toOpenCv(plain);
  CHECK(cv.t == std::array<double, 3>{-1, -2, -3});
  CHECK(cv.distortion == std::vector<double>{0, 0, 0, 0, 0});
}
