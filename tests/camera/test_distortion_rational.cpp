// Distortion.Rational (OpenCV's rational k4..k6 and thin-prism s1..s4 terms): the forward model
// against cv::projectPoints itself with 8- and 12-coefficient vectors, the (non-symmetric) analytic
// Jacobian against central differences, the Newton inverse round trip over a whole image, the
// scene constructor and the coefficient vectors the calibration files write.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "camera/distortion.h"
#include "cameras/rays.h"
#include "distortion_test_util.h"
#include "geometry/prepared_scene.h"
#include "io/opencv_camera.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;

namespace {

// A strong rational model with thin prism: about 5 % radial at the corners of the image below,
// thin-prism terms of a few px; the denominator stays near 1.
DistortionCoefficients<double> strongRational() {
  DistortionCoefficients<double> c;
  c.k1 = -0.28;
  c.k2 = 0.09;
  c.k3 = -0.01;
  c.p1 = 8e-4;
  c.p2 = -5e-4;
  c.k4 = 0.06;
  c.k5 = -0.02;
  c.k6 = 0.004;
  c.s1 = 2e-3;
  c.s2 = -1e-3;
  c.s3 = -1.5e-3;
  c.s4 = 6e-4;
  return c;
}

// A 1200 x 900 camera, fx = 1500 px: normalized coordinates up to ±0.4 × ±0.3.
PinholeModel<double> camera(const DistortionCoefficients<double>& c) {
  PinholeModel<double> m;
  m.fx = 1500;
  m.fy = 1510;
  m.cx = 601.5;
  m.cy = 448.25;
  m.distorted = true;
  m.brown = c;
  return m;
}

// OpenCV's distortion vector (k1, k2, p1, p2, k3, k4, k5, k6[, s1, s2, s3, s4]).
std::vector<double> opencvVector(const DistortionCoefficients<double>& c, bool thinPrism) {
  std::vector<double> v = {c.k1, c.k2, c.p1, c.p2, c.k3, c.k4, c.k5, c.k6};
  if (thinPrism) v.insert(v.end(), {c.s1, c.s2, c.s3, c.s4});
  return v;
}

}  // namespace

TEST_CASE("distortion rational: forward model equals cv::projectPoints (8 and 12 coefficients)") {
  for (bool thinPrism : {false, true}) {
    DistortionCoefficients<double> c = strongRational();
    if (!thinPrism) c.s1 = c.s2 = c.s3 = c.s4 = 0;
    const PinholeModel<double> m = camera(c);
    std::vector<cv::Point3d> points;
    for (double z : {0.3, 1.0, 2.5})
      for (double x = -0.45; x <= 0.45; x += 0.05)
        for (double y = -0.35; y <= 0.35; y += 0.05) points.emplace_back(x * z, y * z, z);
    const cv::Matx33d K(m.fx, 0, m.cx, 0, m.fy, m.cy, 0, 0, 1);
    const std::vector<double> dist = opencvVector(c, thinPrism);
    REQUIRE(dist.size() == (thinPrism ? 12u : 8u));
    std::vector<cv::Point2d> projected;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, dist, projected);
    double worst = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const dvec2 ours = projectToPixel(m, dvec3(points[i].x, points[i].y, points[i].z));
      const double scale = std::max(std::abs(projected[i].x), std::abs(projected[i].y));
      worst = std::max(worst, glm::length(ours - dvec2(projected[i].x, projected[i].y)) / scale);
    }
    MESSAGE(std::string(thinPrism ? "12" : "8") << " coefficients: worst relative difference to cv::projectPoints " << worst);
    // Two double evaluations of the same rational function in different operation orders (OpenCV
    // multiplies out r⁴, r⁶ and the Rodrigues identity rotation): a few ulps, 1e-12 leaves room
    // for ~4000 ulps, far below any wrong term (a swapped or missing coefficient moves pixels by
    // 1e-4 to 1e-2 relative).
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("distortion rational: the analytic Jacobian, not symmetric, matches central differences") {
  const DistortionCoefficients<double> c = strongRational();
  double asymmetry = 0;
  for (double x = -0.4; x <= 0.4; x += 0.08) {
    for (double y = -0.3; y <= 0.3; y += 0.06) {
      const glm::dmat2 J = test::checkJacobianByCentralDifferences(c, dvec2{x, y});
      asymmetry = std::max(asymmetry, std::abs(J[1][0] - J[0][1]));
    }
  }
  // ∂x''/∂y' − ∂y''/∂x' = 2y'tx − 2x'ty: up to ~1e-3 here, so a Newton step that assumed symmetry
  // would be tested by the round trip below.
  CHECK(asymmetry > 1e-4);
}

TEST_CASE("distortion rational: inverse round trip below 1e-9 px over the whole image") {
  const PinholeModel<double> m = camera(strongRational());
  double worst = 0;
  // Every pixel corner of the image (the sensitive area's extreme reach) and every centre, in
  // steps of half a pixel along the border and 2 px inside.
  auto check = [&](double x, double y) {
    const dvec3 d = cameraRayDirection(m, dvec2{x, y});
    REQUIRE(std::isfinite(d.x));
    const dvec2 back = projectToPixel(m, d);
    worst = std::max(worst, std::max(std::abs(back.x - x), std::abs(back.y - y)));
  };
  for (double x = -0.5; x <= 1199.5; x += 0.5) { check(x, -0.5); check(x, 899.5); }
  for (double y = -0.5; y <= 899.5; y += 0.5) { check(-0.5, y); check(1199.5, y); }
  for (double y = 0; y < 900; y += 2)
    for (double x = 0; x < 1200; x += 2) check(x, y);
  MESSAGE("worst round-trip error: " << worst << " px");
  CHECK(worst < 1e-9);
}

TEST_CASE("distortion rational: Brown through the rational formulas is bit-identical") {
  // k4..k6 = s1..s4 = 0 make the extra terms exact no-ops (division by 1, additions of 0), so a
  // Brown camera renders exactly as before Distortion.Rational existed.
  const DistortionCoefficients<double> brown{-0.13, -0.39, 1.20, 1.1e-6, -1.2e-6};
  for (double x = -0.4; x <= 0.4; x += 0.1)
    for (double y = -0.3; y <= 0.3; y += 0.1) {
      const double r2 = x * x + y * y;
      const double rho = 1 + r2 * (brown.k1 + r2 * (brown.k2 + r2 * brown.k3));
      const dvec2 expected{x * rho + 2 * brown.p1 * x * y + brown.p2 * (r2 + 2 * x * x),
                           y * rho + brown.p1 * (r2 + 2 * y * y) + 2 * brown.p2 * x * y};
      CHECK(distort(brown, dvec2{x, y}) == expected);
    }
}

TEST_CASE("distortion rational: scene constructor and OpenCV coefficient vectors") {
  test::TempFolder dir;
  const std::string path = dir.write(
      "scene.lua",
      "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5};\n"
      "  distortion = Distortion.Rational { radial = {0.1, -0.05, 0.01, 0.08}; tangential = {1e-3, -2e-3};\n"
      "                                     thinPrism = {1e-4, 2e-4, 3e-4, 4e-4} } }\n"
      "cam2 = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5};\n"
      "  distortion = Distortion.Rational { radial = {0.1, 0, 0, 0.2, 0.3, 0.4} } }\n");
  const Scene scene = loadScene(path, {});
  REQUIRE(scene.cameras.size() == 2);
  const Distortion& d = scene.cameras[0].distortion;
  CHECK(d.kind == DistortionKind::Rational);
  CHECK(d.k1 == 0.1);
  CHECK(d.k4 == 0.08);
  CHECK(d.k5 == 0.0);
  CHECK(d.p2 == -2e-3);
  CHECK(d.s4 == 4e-4);
  CHECK(toOpenCv(scene.cameras[0]).distortion ==
        std::vector<double>{0.1, -0.05, 1e-3, -2e-3, 0.01, 0.08, 0, 0, 1e-4, 2e-4, 3e-4, 4e-4});
  // Without thin-prism terms OpenCV's 8-coefficient vector.
  CHECK(toOpenCv(scene.cameras[1]).distortion == std::vector<double>{0.1, 0, 0, 0, 0, 0.2, 0.3, 0.4});
  const PreparedScene ps = prepareScene(scene);
  CHECK(ps.features.rationalDistortion);
  CHECK(ps.features.distortion);
}
