// The inverse of a radial distortion against an independent 1-D oracle: the ideal point a lens
// images at a distorted radius R is the root of r·ρ(r) = R joined to the centre, i.e. the first
// crossing of R by r·ρ(r) while it still increases from 0 (and its denominator stays positive).
// Found by scanning r in long double and bisecting, not by Newton. Random Brown and Rational
// models, strong ones included, and random targets; disagreements counted by kind. Newton from the
// target alone refused some models that do not fold (the camera audit of 2026-11-28: Rational
// k4 = -4.2 alone, increasing up to its pole, refused at the image corner).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <algorithm>
#include <random>
#include <vector>

#include "camera/distortion.h"
#include "distortion_test_util.h"
#include "geometry/prepared_scene.h"
#include "scene/scene.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

struct Radial {
  long double k[6];  // k1 k2 k3 (numerator), k4 k5 k6 (denominator)
  long double numerator(long double r2) const { return 1 + r2 * (k[0] + r2 * (k[1] + r2 * k[2])); }
  long double denominator(long double r2) const { return 1 + r2 * (k[3] + r2 * (k[4] + r2 * k[5])); }
  long double distorted(long double r) const { return r * numerator(r * r) / denominator(r * r); }
};

// The branch of r·ρ(r) joined to the centre, tabulated at steps of 1e-4·max(1, r) in r from 0 while
// it increases and its numerator and denominator stay positive (up to r = 1000, or once it passes
// 1.2, beyond every target here). The root for a radius R is found in the table by binary search,
// then by bisection in long double. A fold is a matter of degree at its edge: a dip of the slope
// to -0.001 is a fold the scan sees and a continuation in the plane may step over, and a fold
// whose rise and fall fit in one step is one the scan misses. So the tests leave out of their zero
// counts the roots whose smallest slope on the way is <= 0.05, and the branches that end where
// the slope falls only to -0.05 or above (marginal()).
class Branch {
 public:
  explicit Branch(const Radial& m) : m_(m) {
    r_.push_back(0);
    g_.push_back(0);
    minSlope_.push_back(1);
    while (r_.back() < 1000 && g_.back() <= 1.2L) {
      const long double step = kStep * std::max(1.0L, r_.back());
      const long double next = r_.back() + step;
      if (m.denominator(next * next) <= 0 || m.numerator(next * next) <= 0) break;
      const long double g = m.distorted(next);
      const long double slope = (g - g_.back()) / step;
      if (!(slope > 0)) {
        marginal_ = slope > -0.05L;
        break;
      }
      r_.push_back(next);
      g_.push_back(g);
      minSlope_.push_back(std::min(minSlope_.back(), slope));
    }
  }
  // The root of r·ρ(r) = R on the branch, with the smallest slope up to it; none beyond the branch.
  std::optional<long double> root(long double R, long double& minSlope) const {
    const auto above = std::upper_bound(g_.begin(), g_.end(), R);
    if (above == g_.end()) return std::nullopt;
    const std::size_t i = std::size_t(above - g_.begin());  // g_[i - 1] <= R < g_[i]
    if (i == 0) return std::nullopt;                          // R < 0: not a radius
    minSlope = minSlope_[i];
    long double lo = r_[i - 1], hi = r_[i];
    for (int b = 0; b < 80; ++b) {
      const long double mid = (lo + hi) / 2;
      (m_.distorted(mid) < R ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
  }
  // The branch ended at a fold whose slope falls only to -0.05 or above: a marginal one.
  bool marginal() const { return marginal_; }

 private:
  static constexpr long double kStep = 1e-4L;
  Radial m_;
  std::vector<long double> r_, g_, minSlope_;
  bool marginal_ = false;
};

// A random radial model: Brown (k1..k3) or, every other one, Rational (k4..k6 too); a quarter strong.
DistortionCoefficients<double> randomRadial(std::mt19937_64& rng, int model, Radial& m) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  DistortionCoefficients<double> c;
  const double strength = model % 4 == 0 ? 5.0 : 1.0;
  c.k1 = strength * u(rng);
  c.k2 = strength * u(rng);
  c.k3 = strength * u(rng);
  if (model % 2 == 1) {  // rational: poles within reach where the denominator's terms are negative
    c.k4 = strength * u(rng);
    c.k5 = strength * u(rng);
    c.k6 = strength * u(rng);
  }
  const double k[6] = {c.k1, c.k2, c.k3, c.k4, c.k5, c.k6};
  for (int i = 0; i < 6; ++i) m.k[i] = k[i];
  return c;
}

// The oracle's ideal point for `target`: its direction (a radial model keeps it), the root's radius.
std::optional<glm::dvec2> oracleIdeal(const Branch& branch, glm::dvec2 target, long double& minSlope) {
  const long double R = std::hypot((long double)target.x, (long double)target.y);
  if (R == 0) {
    minSlope = 1;
    return target;
  }
  const std::optional<long double> root = branch.root(R, minSlope);
  if (!root) return std::nullopt;
  const long double scale = *root / R;
  return glm::dvec2{double(target.x * scale), double(target.y * scale)};
}

// Two roots agree to 1e-12 normalized (~1e-9 px at fx = 1000 px, the round trip the docs promise):
// the root's own error is the stopping step's, 1e-14, times the inverse slope (<= 1/0.05 here).
bool sameRoot(glm::dvec2 a, glm::dvec2 b, long double minSlope) {
  return glm::length(a - b) <= 1e-12 * std::max(1.0, 1.0 / double(minSlope));
}

}  // namespace

TEST_CASE("distortion inverse: where Newton from the target fails, the path from the centre finds the oracle's root") {
  // Random targets up to radius 1.1 (normalized) on random radial models. Where Newton from the
  // target fails, undistort() follows the path from the centre: it must return the oracle's root
  // where there is one, and NaN where there is none. A root whose slope falls below 0.05 on the
  // way is left out of the refusal count (a stretch that flat needs steps below 1/1024; the scan's
  // own resolution, 1e-5, also limits the oracle there).
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long long targets = 0, newtonAlone = 0, agree = 0, wrongRoot = 0, refusedWithRoot = 0, rootWithoutOracle = 0,
            noRootBoth = 0, exempt = 0;
  for (int model = 0; model < 2000; ++model) {
    Radial m{};
    const DistortionCoefficients<double> c = randomRadial(rng, model, m);
    const Branch branch(m);
    for (int t = 0; t < 20; ++t) {
      const double R = 1.1 * unit(rng), angle = 6.283185307179586 * unit(rng);
      const glm::dvec2 target{R * std::cos(angle), R * std::sin(angle)};
      ++targets;
      glm::dvec2 newton;
      if (undistortNewton(c, target, target, newton)) {
        ++newtonAlone;  // its root may be another one: prepare's check (next test case) compares
        continue;
      }
      long double minSlope = 0;
      const std::optional<glm::dvec2> expected = oracleIdeal(branch, target, minSlope);
      const glm::dvec2 p = undistort(c, target);
      if (!expected) {
        if (std::isnan(p.x)) ++noRootBoth;
        else (branch.marginal() ? exempt : rootWithoutOracle) += 1;
      } else if (std::isnan(p.x)) {
        (minSlope > 0.05 ? refusedWithRoot : exempt) += 1;
      } else if (sameRoot(p, *expected, minSlope)) {
        ++agree;
      } else {
        ++wrongRoot;
      }
    }
  }
  MESSAGE(targets << " targets: Newton from the target converged on " << newtonAlone << "; of the others, "
                  << agree << " equal the oracle, " << noRootBoth << " have no root for both, " << wrongRoot
                  << " wrong roots, " << refusedWithRoot << " refused with a root, " << rootWithoutOracle
                  << " roots where the oracle has none, " << exempt << " left out (marginal folds)");
  CHECK(wrongRoot == 0);
  CHECK(refusedWithRoot == 0);
  CHECK(rootWithoutOracle == 0);
  CHECK(agree > 500);
  CHECK(exempt < targets / 1000);  // the path was taken and found roots Newton from the target missed
}

TEST_CASE("distortion inverse: a camera prepare accepts inverts every image point to the oracle's root") {
  // Random 64 x 48 px cameras whose image corner lies at normalized radius 0.2..1.0, with random
  // radial models. Accepted (prepareScene): 300 random sample positions in the sensitive area must
  // invert to the oracle's root (no wrong root, no NaN). Refused: some position on a 1 px grid must
  // have no root joined to the centre, or a second root that Newton from the target reaches; else
  // the refusal was needless. Counted by kind; zero allowed for wrong roots and needless refusals.
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long long accepted = 0, refused = 0, wrongRoot = 0, missedRefusal = 0, needlessRefusal = 0;
  for (int model = 0; model < 600; ++model) {
    Radial m{};
    const DistortionCoefficients<double> c = randomRadial(rng, model, m);
    const Branch branch(m);
    const double cornerRadius = 0.2 + 0.8 * unit(rng);
    const double f_px = std::hypot(32.0, 24.0) / cornerRadius;
    Distortion distortion{model % 2 == 1 ? DistortionKind::Rational : DistortionKind::Brown, c.k1, c.k2, c.k3, 0, 0};
    distortion.k4 = c.k4;
    distortion.k5 = c.k5;
    distortion.k6 = c.k6;
    const Scene scene = test::distortedCameraScene({"random.lua", 1}, "camera", 64, 48, f_px * 1e-5, 1e-5, distortion);
    auto position = [&](double x, double y) { return glm::dvec2{(x - 31.5) / f_px, (y - 23.5) / f_px}; };
    bool isRefused = false;
    try {
      prepareScene(scene);
    } catch (const InputError& e) {
      isRefused = true;
      CHECK(std::string(e.what()).find("cannot be inverted at image position") != std::string::npos);
    }
    if (!isRefused) {
      ++accepted;
      for (int i = 0; i < 300; ++i) {
        const glm::dvec2 target = position(-0.5 + 64 * unit(rng), -0.5 + 48 * unit(rng));
        long double minSlope = 0;
        const std::optional<glm::dvec2> expected = oracleIdeal(branch, target, minSlope);
        const glm::dvec2 p = undistort(c, target);
        if (!expected) missedRefusal += branch.marginal() ? 0 : 1;
        else if (std::isnan(p.x) || !sameRoot(p, *expected, minSlope)) ++wrongRoot;
      }
      continue;
    }
    ++refused;
    bool reason = false;
    for (double y = -0.5; y <= 47.5 && !reason; y += 1)
      for (double x = -0.5; x <= 63.5 && !reason; x += 1) {
        const glm::dvec2 target = position(x, y);
        long double minSlope = 0;
        const std::optional<glm::dvec2> expected = oracleIdeal(branch, target, minSlope);
        glm::dvec2 newton;
        reason = !expected || minSlope <= 0.05 || branch.marginal() ||
                 (undistortNewton(c, target, target, newton) && !sameRoot(newton, *expected, minSlope));
      }
    if (!reason) ++needlessRefusal;
  }
  MESSAGE(accepted << " cameras accepted, " << refused << " refused; " << wrongRoot << " wrong roots, "
                   << missedRefusal << " positions without a root in accepted cameras, " << needlessRefusal
                   << " needless refusals");
  CHECK(wrongRoot == 0);
  CHECK(needlessRefusal == 0);
  // A fold narrower than the check's 8 px grid can slip between its points; none did here.
  CHECK(missedRefusal == 0);
  CHECK(accepted > 100);
  CHECK(refused > 100);
}

TEST_CASE("distortion inverse: a refusal at a near-hemispherical field of view names focalLength and pixelSize") {
  // pixelSize = {6.9, 6.9} (µm typed as metres) made fx = 0.0017 px and the message said only
  // "check the coefficients" (the new-user trial of 2026-11-28). Beyond a normalized corner radius
  // of 10 (84°) it names the focal length, the pixel size and their unit; a real fold does not.
  const Distortion brown{DistortionKind::Brown, -0.08, 0.05, 0, 1e-4, -2e-4};
  const auto messageOf = [&](double pixel_m, const Distortion& distortion) {
    try {
      prepareScene(test::distortedCameraScene({"um.lua", 4}, "left", 800, 600, 0.012, pixel_m, distortion));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string wrongUnit = messageOf(6.9, brown);
  CHECK(wrongUnit.find("um.lua:4: Distortion.Brown of camera 'left' cannot be inverted") == 0);
  CHECK(wrongUnit.find("degrees off the axis: fx = 0.00173913 px, fy = 0.00173913 px; check focalLength and pixelSize, "
                       "both in metres, then the coefficients)") != std::string::npos);
  // A real fold within a wide but sane field: r (1 − 0.3 r²) turns back at r = 1.05, the corner at
  // radius 4.2 (fx = 120 px): the coefficients' fault.
  const std::string fold = messageOf(1e-4, Distortion{DistortionKind::Brown, -0.3, 0, 0, 0, 0});
  CHECK(fold.find("cannot be inverted") != std::string::npos);
  CHECK(fold.find("(check the coefficients)") != std::string::npos);
  CHECK(fold.find("pixelSize") == std::string::npos);
  CHECK(messageOf(6.9e-6, brown).empty());  // the size meant: accepted
}

TEST_CASE("distortion inverse: a telecentric camera's refusal names magnification and pixelSize, not focalLength") {
  // pixelSize = {5, 5} (µm typed as metres) on a Camera.Orthographic: the message said "degrees off
  // the axis" and "check focalLength", a key that camera refuses (the camera trial of 2026-11-29).
  // Its normalized coordinates are metres on the object side: the corner lies 4,000 m out.
  test::TempFolder folder;
  const std::string path = folder.write("tele.lua",
      "camera = Camera.Orthographic { resolution = {640, 480}; pixelSize = {5, 5}; magnification = 0.5;\n"
      "  distortion = Distortion.Brown { radial = {-200} } }\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.02, 0.02}; location = {0, 0, 0.1} };\n"
      "  shader = Shader.Constant { color = 0.5 } }\n");
  std::string message;
  try {
    prepareScene(loadScene(path, {}));
  } catch (const InputError& e) {
    message = e.what();
  }
  INFO(message);
  CHECK(message.find("/tele.lua:1: Distortion.Brown of camera 'camera' cannot be inverted") != std::string::npos);
  CHECK(message.find("m from the axis on the object side: fx = 0.1 and fy = 0.1 px per metre; check magnification and "
                     "pixelSize (in metres)") != std::string::npos);
  CHECK(message.find("focalLength") == std::string::npos);
  CHECK(message.find("degrees") == std::string::npos);
}
