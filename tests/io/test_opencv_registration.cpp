// "A check that no one can fake" (issue 4): a speckled plane translated by a known sub-pixel
// amount, registered by OpenCV's ECC (an independent implementation that knows nothing of our
// ground truth), must move by the ground-truth flow.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>


#include <opencv2/core.hpp>
#include <opencv2/video/tracking.hpp>

#include "core/math.h"
#include "cpu/reference_renderer.h"
#include "files/image_io.h"
#include "render/ground_truth.h"
#include "scene/scene.h"
#include "temp_folder.h"
#include "texture/speckle.h"

namespace dicsynth {
namespace {

// A 256 x 256 camera 0.4 m from a fronto-parallel speckled square that fills the view; fx =
// 0.016 / 4e-6 = 4000 px, so a translation of d metres along x moves the image by 10^4 d px. The
// square (0.1 m) carries a 1024-texel speckle: one texel (98 µm) per image pixel (100 µm), disks
// of radius 2.5 texels, i.e. speckles 5 px across, as DIC practice recommends.
std::string scene() {
  return "camera = Camera.Pinhole { resolution = {256, 256}; focalLength = 0.016; pixelSize = {4e-6, 4e-6} }\n"
         "specimen = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.1}; location = {shift_px / 1e4, 0, 0.4} };"
         " texture = Texture.File { fileName = \"speckle.tif\" } }\n";
}

struct Frame {
  PreparedScene scene;
  RenderResult result;
};

Frame render(const std::string& path, double shift_px) {
  char value[32];
  std::snprintf(value, sizeof value, "%.17g", shift_px);
  Frame f{prepareScene(loadScene(path, {{{"shift_px", value}}, 0})), {}};
  RenderOptions options;
  options.samplesPerPixel = 64;
  f.result = cpu::render(f.scene, options);
  return f;
}

cv::Mat image(const RenderResult& r) {
  const CameraImage& c = r.cameras[0];
  cv::Mat m(c.height_px, c.width_px, CV_32F);
  for (int y = 0; y < c.height_px; ++y)
    for (int x = 0; x < c.width_px; ++x) m.at<float>(y, x) = float(c.radiance[std::size_t(y) * c.width_px + x]);
  return m;
}

}  // namespace

// ECC (Evangelidis & Psarakis 2008) as OpenCV implements it: translation model, 5x5 Gaussian
// pre-filter on both images, bilinear warping, the 16-px border masked out (pixels whose content
// enters from outside the view). Returns the shift of `moved`'s content relative to `reference`.
dvec2 ecc(const cv::Mat& reference, const cv::Mat& moved, const cv::Mat& mask) {
  cv::Mat warp = cv::Mat::eye(2, 3, CV_32F);
  cv::findTransformECC(reference, moved, warp, cv::MOTION_TRANSLATION,
                       cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 500, 1e-10), mask, 5);
  return {warp.at<float>(0, 2), warp.at<float>(1, 2)};
}

TEST_CASE("opencv: ECC registration of a translated speckle measures the ground-truth flow") {
  test::TempFolder dir;
  const std::string path = dir.write("plane.lua", scene());
  SpeckleParams speckle;
  speckle.radius_px = 2.5;
  const GrayImage texture = generateSpeckle(speckle);
  std::vector<std::uint16_t> values(texture.pixels.size());
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::uint16_t(std::lround(texture.pixels[i] * 65535));
  writeGrayTiff(dir.file("speckle.tif"), texture.width, texture.height, values, 16, "test speckle");

  const Frame ref = render(path, 0);
  const cv::Mat refImage = image(ref.result);
  const ReferenceFrame reference(0, ref.scene, ref.result);
  cv::Mat mask = cv::Mat::zeros(256, 256, CV_8U);
  mask(cv::Rect(16, 16, 224, 224)) = 255;

  // The registration's own accuracy, without our renderer: the reference image against exact
  // copies of itself moved by whole pixels (crops of one image, so nothing is interpolated or
  // invented). Measured: 1.4e-3 px (OpenCV's ECC works in float32 and blurs the borders of its
  // mask). Required below 2e-3 px, or the check below would not mean much.
  double eccError = 0;
  cv::Mat cropMask = cv::Mat::zeros(224, 224, CV_8U);
  cropMask(cv::Rect(8, 8, 208, 208)) = 255;  // the same kind of border as for the full images
  for (int k : {-1, 1}) {
    const cv::Mat a = refImage(cv::Rect(16, 16, 224, 224)), b = refImage(cv::Rect(16 - k, 16, 224, 224));
    eccError = std::max(eccError, glm::length(ecc(a, b, cropMask) - dvec2(k, 0)));
  }
  MESSAGE("ECC error on exact whole-pixel copies: " << eccError << " px");
  REQUIRE(eccError < 2e-3);

  // 0.05 px as the issue asks, and 0.5 px where a 0.5 % error in the rendered motion would show.
  for (double shift : {0.05, 0.5}) {
    CAPTURE(shift);
    const Frame cur = render(path, shift);
    const DerivedTruth truth = deriveTruth(reference, 1, cur.scene, cur.result, 0);
    // The ground truth: fronto-parallel, no distortion, so the flow is the shift at every pixel.
    dvec2 flowMin(1e9), flowMax(-1e9);
    for (int y = 16; y < 240; ++y)
      for (int x = 16; x < 240; ++x) {
        flowMin = glm::min(flowMin, truth.flow_px[std::size_t(y) * 256 + x]);
        flowMax = glm::max(flowMax, truth.flow_px[std::size_t(y) * 256 + x]);
      }
    CHECK(flowMax.x - flowMin.x < 1e-12);
    CHECK(std::abs(flowMin.x - shift) < 1e-12);
    const dvec2 measured = ecc(refImage, image(cur.result), mask);
    MESSAGE("shift " << shift << " px: ECC measures " << measured.x << ", " << measured.y << " px");
    // Within the registration's own accuracy: twice its error on exact copies, the second half
    // for what the copies lack, the rendering's Monte Carlo noise (64 stratified samples: rms
    // 0.3 % of the speckle contrast between two renders). Measured: 5.6e-4 px at 0.05 px, 8.2e-4 px at
    // 0.5 px. At 0.5 px the bound (≤ 4e-3 px) catches a 1 % error of scale in the rendered motion.
    CHECK(glm::length(measured - flowMin) < 2 * eccError);
  }
}

}  // namespace dicsynth
