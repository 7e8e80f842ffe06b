// Brown distortion: forward model against OpenCV's formula evaluated independently in long double,
// the analytic Jacobian against finite differences, the Newton inverse round trip over a whole
// image (corners included), and the refusal of a distortion that folds inside the image.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "camera/distortion.h"
#include "cameras/rays.h"
#include "distortion_test_util.h"
#include "geometry/prepared_scene.h"

using namespace dicsynth;

namespace {

// OpenCV's documented model (calib3d, "Detailed Description"), written out term by term.
dvec2 opencvDistort(long double k1, long double k2, long double k3, long double p1, long double p2,
                    long double x, long double y) {
  const long double r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
  const long double radial = 1 + k1 * r2 + k2 * r4 + k3 * r6;
  return {double(x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)),
          double(y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y)};
}

// Figure 1 of the paper.
const BrownCoefficients<double> kFigure1{-0.13, -0.39, 1.20, 1.1e-6, -1.2e-6};
const BrownCoefficients<double> kStrongTangential{-0.2, 0.05, 0.0, 2e-3, -1.5e-3};

}  // namespace

TEST_CASE("distortion: forward model equals OpenCV's formula") {
  for (const auto& c : {kFigure1, kStrongTangential}) {
    for (double x = -0.4; x <= 0.4; x += 0.05) {
      for (double y = -0.3; y <= 0.3; y += 0.05) {
        const dvec2 ours = distort(c, dvec2{x, y});
        const dvec2 ref = opencvDistort(c.k1, c.k2, c.k3, c.p1, c.p2, x, y);
        // Both are double evaluations of a degree-7 polynomial of |x| < 1: a few ulps apart.
        CHECK(std::abs(ours.x - ref.x) < 1e-15);
        CHECK(std::abs(ours.y - ref.y) < 1e-15);
      }
    }
  }
}

TEST_CASE("distortion: analytic Jacobian matches central differences") {
  for (const auto& c : {kFigure1, kStrongTangential}) {
    for (double x = -0.35; x <= 0.35; x += 0.07)
      for (double y = -0.25; y <= 0.25; y += 0.05) test::checkJacobianByCentralDifferences(c, dvec2{x, y});
  }
}

TEST_CASE("distortion: inverse round trip below 1e-9 px over the whole Figure 1 image") {
  // Figure 1's camera: 1600 x 1200, f = 12 mm, 4.4 µm pixels → fx = fy = 2727.27 px.
  PinholeModel<double> m;
  m.fx = m.fy = 0.012 / 4.4e-6;
  m.cx = 800;
  m.cy = 600;
  m.distorted = true;
  m.brown = kFigure1;
  double worst = 0;
  // Every pixel corner of the image (the sensitive area's extreme reach) and every centre.
  for (double y = -0.5; y <= 1199.5; y += 0.5) {
    for (double x = -0.5; x <= 1599.5; x += 0.5) {
      const dvec3 d = cameraRayDirection(m, dvec2{x, y});
      REQUIRE(std::isfinite(d.x));
      const dvec2 back = projectToPixel(m, d);  // camera at the origin, identity pose
      worst = std::max(worst, std::max(std::abs(back.x - x), std::abs(back.y - y)));
    }
  }
  MESSAGE("worst round-trip error: " << worst << " px");
  CHECK(worst < 1e-9);
}

TEST_CASE("distortion: the lockstep inverse equals undistort() bit for bit, failures included") {
  // undistortLockstep<8> interleaves eight Newton iterations; each target must get undistort()'s
  // very bits. Random models (Brown, rational, thin prism; some strong enough to fold or not to
  // converge, giving NaN) and random targets, many beyond where the model is invertible, with
  // +0 and -0 among them; disagreements counted by kind.
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::size_t targets = 0, nanBoth = 0, differing = 0, nanMismatch = 0;
  for (int model = 0; model < 300; ++model) {
    DistortionCoefficients<double> c;
    const double strength = model % 3 == 0 ? 2.0 : 0.3;  // a third of them fold inside the range
    c.k1 = strength * u(rng);
    c.k2 = strength * u(rng);
    c.k3 = strength * u(rng);
    c.p1 = 0.01 * u(rng);
    c.p2 = 0.01 * u(rng);
    if (model % 2 == 1) {  // rational and thin prism
      c.k4 = 0.3 * u(rng);
      c.k5 = 0.1 * u(rng);
      c.k6 = 0.1 * u(rng);
      c.s1 = 0.01 * u(rng);
      c.s2 = 0.01 * u(rng);
      c.s3 = 0.01 * u(rng);
      c.s4 = 0.01 * u(rng);
    }
    dvec2 target[8], lockstep[8];
    for (int batch = 0; batch < 40; ++batch) {
      for (dvec2& t : target) t = dvec2{0.9 * u(rng), 0.9 * u(rng)};
      if (batch == 0) {
        target[0] = dvec2{0.0, 0.0};
        target[1] = dvec2{-0.0, 0.3};
        target[2] = dvec2{0.25, -0.0};
      }
      undistortLockstep<8>(c, target, lockstep);
      for (int l = 0; l < 8; ++l) {
        ++targets;
        const dvec2 one = undistort(c, target[l]);
        const bool nanOne = std::isnan(one.x), nanLockstep = std::isnan(lockstep[l].x);
        if (nanOne && nanLockstep) ++nanBoth;
        else if (nanOne != nanLockstep) ++nanMismatch;
        else if (std::memcmp(&one, &lockstep[l], sizeof one) != 0) ++differing;
      }
    }
  }
  MESSAGE(targets << " targets, " << nanBoth << " not invertible by either");
  CHECK(differing == 0);
  CHECK(nanMismatch == 0);
  CHECK(nanBoth > 100);               // the failure paths were taken
  CHECK(nanBoth < targets / 2);       // and most targets converged
}

TEST_CASE("distortion: float Newton converges to float accuracy") {
  const BrownCoefficients<float> c{-0.13f, -0.39f, 1.20f, 1.1e-6f, -1.2e-6f};
  for (float x = -0.29f; x <= 0.29f; x += 0.01f) {
    const glm::vec2 target{x, 0.75f * x};
    const glm::vec2 p = undistort(c, target);
    const dvec2 back = distort(kFigure1, dvec2(p));
    // A few float ulps of 0.3: 1e-7 normalized ≈ 3e-4 px at fx = 2727 px.
    CHECK(std::abs(back.x - target.x) < 2e-7);
    CHECK(std::abs(back.y - target.y) < 2e-7);
  }
}

TEST_CASE("distortion: a distortion that folds inside the image is refused") {
  // ρ r = r − 4 r³ folds at r = 0.289.
  Scene scene = test::distortedCameraScene({"fold.lua", 3}, "camera1", 1600, 1200, 0.012, 4.4e-6,
                                           {DistortionKind::Brown, -4.0, 0, 0, 0, 0});
  try {
    prepareScene(scene);
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    CHECK(msg.rfind("fold.lua:3: ", 0) == 0);
    CHECK(msg.find("cannot be inverted") != std::string::npos);
  }
  scene.cameras[0].distortion.k1 = -0.13;  // Figure 1's k1 alone is fine
  CHECK_NOTHROW(prepareScene(scene));
}
