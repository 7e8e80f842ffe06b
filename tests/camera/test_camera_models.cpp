// Camera.ThinLens and Camera.Orthographic against closed forms, rendered by the CPU reference:
// the blur of an out-of-focus edge against the blur-circle diameter c = A v |1/u − 1/d|, the plane
// in focus as sharp as the pinhole of focal length v, f-number ≡ diameter; a telecentric camera's
// magnification independent of depth; the lens samples uniform on the disk; the constructors' errors.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "camera/sampling.h"
#include "core/exact_number.h"
#include "cpu/reference_renderer.h"
#include "cpu/trace.h"
#include "exr_test_util.h"
#include "geometry/prepared_scene.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "io/calibration_files.h"
#include "render/compare.h"
#include "render/ground_truth.h"
#include "render/image_point.h"
#include "render/target_features.h"
#include "run_cli.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;

namespace {

constexpr double kPi = 3.14159265358979323846;

PreparedScene prepared(const test::TempFolder& dir, const std::string& text) {
  return prepareScene(loadScene(dir.write("scene.lua", text), {}));
}

RenderResult renderCpu(const PreparedScene& scene, int spp) {
  RenderOptions options;
  options.samplesPerPixel = spp;
  options.seed = 7;
  return cpu::render(scene, options);
}

// A bright half-plane x ≥ 0 (world) at depth d on black, seen by `camera` (Lua text).
std::string edgeScene(const std::string& camera, double depth) {
  return "cam = " + camera + "\n" +
         "edge = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0.5, 0, " +
         std::to_string(depth) + "} }; shader = Shader.Constant { color = 1 } }\n";
}

// Fraction of the unit disk with a ≤ t: (π − acos t + t √(1 − t²)) / π, clamped.
double diskFractionBelow(double t) {
  if (t <= -1) return 0;
  if (t >= 1) return 1;
  return (kPi - std::acos(t) + t * std::sqrt(1 - t * t)) / kPi;
}

const char* kThinLens =
    "Camera.ThinLens { resolution = {64, 16}; pixelSize = {1e-5, 1e-5}; focalLength = 0.05; "
    "fNumber = 8; focusDistance = 0.5 }";

}  // namespace

TEST_CASE("camera thin lens: an out-of-focus edge is blurred by the blur circle c = A v |1/u - 1/d|") {
  test::TempFolder dir;
  const double f = 0.05, N = 8, u = 0.5, d = 0.6, s = 1e-5;
  const PreparedScene scene = prepared(dir, edgeScene(kThinLens, d));
  const auto& m = scene.cameras[0].model;
  const double A = f / N, v = f * u / (u - f);
  CHECK(m.fx == doctest::Approx(v / s).epsilon(1e-15));
  const double c_px = A * v * std::abs(1 / u - 1 / d) / s;  // blur-circle diameter on the sensor, px
  MESSAGE("blur circle: " << c_px << " px");
  const int spp = 256;
  const RenderResult r = renderCpu(scene, spp);
  const CameraImage& img = r.cameras[0];
  // The edge's chief-ray image lies at x = cx; a pixel's value is the fraction of its rays (pixel
  // square × lens disk) that meet x ≥ 0 at depth d. A lens point a (units of R) shifts the ray's
  // landing point by R a (1 − d/u), i.e. by −(c/2) a px in the image: value(x) = mean over the
  // pixel's width of diskFractionBelow((x − cx) / (c/2)) (midpoint rule, 2000 points: exact to 1e-6).
  double worst = 0;
  for (int x = 0; x < img.width_px; ++x) {
    double expected = 0;
    for (int k = 0; k < 2000; ++k) {
      const double xs = x - 0.5 + (k + 0.5) / 2000;
      expected += diskFractionBelow((xs - m.cx) / (0.5 * c_px)) / 2000;
    }
    double mean = 0;
    for (int y = 0; y < img.height_px; ++y) mean += img.radiance[std::size_t(y * img.width_px + x)];
    mean /= img.height_px;
    worst = std::max(worst, std::abs(mean - expected));
  }
  // Each column averages 16 rows × 256 samples = 4096 Bernoulli draws: standard deviation at most
  // 0.5/√4096 = 0.0078; 5σ = 0.039. A blur circle 20 % too small or too large moves the profile's
  // slopes by ~0.1.
  MESSAGE("worst column difference to the closed form: " << worst);
  CHECK(worst < 0.039);
  // And the profile reaches 0 and 1 exactly where the blur ends: c/2 + ½ px from the edge.
  const int reach = int(std::ceil(0.5 * c_px + 0.5));
  for (int y = 0; y < img.height_px; ++y) {
    CHECK(img.radiance[std::size_t(y * img.width_px + int(m.cx) - reach - 1)] == 0.0);
    CHECK(img.radiance[std::size_t(y * img.width_px + int(m.cx) + reach + 2)] == 1.0);
  }
}

TEST_CASE("camera thin lens: the plane in focus is exactly the pinhole image of focal length v") {
  test::TempFolder dir;
  const double f = 0.05, u = 0.5, v = f * u / (u - f);
  const PreparedScene lens = prepared(dir, edgeScene(kThinLens, u));
  const PreparedScene pinhole = prepared(
      dir, edgeScene("Camera.Pinhole { resolution = {64, 16}; pixelSize = {1e-5, 1e-5}; focalLength = " +
                         exactNumber(v) + " }",
                     u));
  CHECK(lens.cameras[0].model.fx == pinhole.cameras[0].model.fx);
  const RenderResult a = renderCpu(lens, 16), b = renderCpu(pinhole, 16);
  // Every ray of a pixel sample passes through the same point of the plane in focus as the pinhole
  // ray; the hit points differ by rounding (1e-17 m), so a sample value could change only if a
  // sample fell within 1e-12 px of the edge: none does.
  double worst = 0;
  for (std::size_t i = 0; i < a.cameras[0].radiance.size(); ++i)
    worst = std::max(worst, std::abs(a.cameras[0].radiance[i] - b.cameras[0].radiance[i]));
  CHECK(worst == 0.0);
  // The edge itself is sharp: one column of intermediate values at most.
  int grey = 0;
  for (int x = 0; x < 64; ++x) grey += a.cameras[0].radiance[std::size_t(x)] > 0 && a.cameras[0].radiance[std::size_t(x)] < 1;
  CHECK(grey <= 1);
  // Ground truth: the chief ray, the pinhole's.
  for (std::size_t i = 0; i < a.cameras[0].depth_m.size(); ++i) {
    CHECK(a.cameras[0].objectId[i] == b.cameras[0].objectId[i]);
    if (a.cameras[0].objectId[i]) CHECK(a.cameras[0].position_m[i] == b.cameras[0].position_m[i]);
  }
}

TEST_CASE("camera thin lens: fNumber and aperture diameter are equivalent") {
  test::TempFolder dir;
  const PreparedScene byNumber = prepared(dir, edgeScene(kThinLens, 0.6));
  const PreparedScene byDiameter = prepared(
      dir, edgeScene("Camera.ThinLens { resolution = {64, 16}; pixelSize = {1e-5, 1e-5}; focalLength = 0.05; "
                     "aperture = 0.00625; focusDistance = 0.5 }",
                     0.6));
  CHECK(std::get<cameras::ThinLens>(byNumber.cameras[0].camera.model).aperture_m == 0.00625);
  CHECK(byNumber.cameras[0].model.lensRadius == byDiameter.cameras[0].model.lensRadius);
  const RenderResult a = renderCpu(byNumber, 4), b = renderCpu(byDiameter, 4);
  CHECK(a.cameras[0].radiance == b.cameras[0].radiance);
}

TEST_CASE("camera thin lens: lens samples are uniform on the unit disk") {
  // Moments of the uniform disk: E[a] = E[b] = 0, E[a²] = E[b²] = 1/4, E[r²] = 1/2; every point
  // strictly inside. 40 000 samples: σ(mean of a) = 0.5/200 = 0.0025, σ(mean of a²) ≈ 0.0011.
  double sa = 0, sb = 0, saa = 0, sbb = 0, sr = 0;
  int inner = 0;  // r < 1/√2 holds half of the disk's area
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    const dvec2 p = lensSample<double>(1, 0, 0, uint(i % 200), uint(i / 200), uint(i % 7));
    REQUIRE(glm::dot(p, p) < 1.0);
    sa += p.x;
    sb += p.y;
    saa += p.x * p.x;
    sbb += p.y * p.y;
    sr += glm::dot(p, p);
    inner += glm::dot(p, p) < 0.5;
  }
  CHECK(std::abs(sa / n) < 5 * 0.0025);
  CHECK(std::abs(sb / n) < 5 * 0.0025);
  CHECK(std::abs(saa / n - 0.25) < 5 * 0.0011);
  CHECK(std::abs(sbb / n - 0.25) < 5 * 0.0011);
  CHECK(std::abs(sr / n - 0.5) < 5 * 0.0015);   // σ(r²) = 1/√12 → 0.0014
  CHECK(std::abs(double(inner) / n - 0.5) < 5 * 0.0025);
}

TEST_CASE("camera orthographic: magnification independent of depth, x = cx + m X / pixelSize") {
  test::TempFolder dir;
  const double m = 0.5, s = 1e-5;
  const std::string cam =
      "Camera.Orthographic { resolution = {80, 60}; pixelSize = {1e-5, 1e-5}; magnification = 0.5; "
      "position = {0.0002, -0.0001, -0.05} }";
  for (double depth : {0.02, 0.4}) {
    const PreparedScene scene = prepared(dir, edgeScene(cam, depth));
    const PreparedCamera& pc = scene.cameras[0];
    // Projection of world points: the closed form, whatever their depth.
    for (double X : {-0.0007, 0.0, 0.0011}) {
      const dvec2 px = projectToPixel(pc.model, dvec3(X, 0.0003, depth));
      CHECK(px.x == doctest::Approx(pc.model.cx + m * (X - 0.0002) / s).epsilon(1e-13));
      CHECK(px.y == doctest::Approx(pc.model.cy + m * (0.0003 + 0.0001) / s).epsilon(1e-13));
    }
    // Rendered: the ray of pixel (x, y) meets the plane at X = 0.0002 + (x − cx) s / m (its chief
    // ray starts on the plane Z = 0 and runs along the axis), at depth Z = depth + 0.05.
    const RenderResult r = renderCpu(scene, 1);
    const CameraImage& img = r.cameras[0];
    int lit = 0;
    for (int y = 0; y < img.height_px; ++y)
      for (int x = 0; x < img.width_px; ++x) {
        const std::size_t i = std::size_t(y * img.width_px + x);
        const double X = 0.0002 + (x - pc.model.cx) * s / m;
        if (X > 1e-12) {
          REQUIRE(img.objectId[i] == 1);
          CHECK(img.position_m[i].x == doctest::Approx(X).epsilon(1e-12));
          CHECK(img.position_m[i].y == doctest::Approx(-0.0001 + (y - pc.model.cy) * s / m).epsilon(1e-12));
          CHECK(img.depth_m[i] == doctest::Approx(depth + 0.05).epsilon(1e-14));
          ++lit;
        } else if (X < -1e-12) {
          CHECK(img.objectId[i] == 0);
        }
      }
    // The edge at X = 0 appears at x = cx − m·0.0002/s = cx − 10 at both depths: columns 0..29 dark.
    CHECK(lit == 60 * (80 - 30));
    // The visibility test of the ground truth follows the axis, not a line to a centre.
    CHECK(reachesFirst(scene, pc, 0, dvec3(0.001, 0.0002, depth), 1e-9));
  }
}

TEST_CASE("camera orthographic: nothing behind the plane Z = 0 is seen") {
  test::TempFolder dir;
  const PreparedScene scene = prepared(
      dir, edgeScene("Camera.Orthographic { resolution = {8, 6}; pixelSize = {1e-5, 1e-5}; magnification = 1; "
                     "position = {0.0001, 0, 0.1} }",
                     0.05));
  const RenderResult r = renderCpu(scene, 1);
  for (std::uint32_t id : r.cameras[0].objectId) CHECK(id == 0);
  CHECK_FALSE(projectToImage(scene.cameras[0], dvec3(0.0001, 0, 0.05)).inFront);
}

TEST_CASE("camera models: calibration files state what OpenCV's model cannot") {
  test::TempFolder dir;
  const Scene scene = loadScene(
      dir.write("scene.lua",
                "a = " + std::string(kThinLens) +
                    "\nb = Camera.Orthographic { resolution = {8, 6}; pixelSize = {1e-5, 2e-5}; magnification = 0.25 }\n"),
      {});
  const auto files = calibrationFiles(scene.cameras, {}, "");
  REQUIRE(files.size() == 2);
  CHECK(files[0].text.find("camera_model: \"thin_lens\"") != std::string::npos);
  CHECK(files[0].text.find("focus_distance_m: 0.5") != std::string::npos);
  CHECK(files[1].text.find("camera_model: \"orthographic\"") != std::string::npos);
  CHECK(files[1].text.find("magnification: 0.25") != std::string::npos);
  // Orthographic camera matrix: px per metre of object.
  CHECK(files[1].text.find("data: [ " + exactNumber(0.25 / 1e-5) + ", 0, 3.5, 0, " + exactNumber(0.25 / 2e-5) +
                           ", 2.5, 0, 0, 1 ]") != std::string::npos);
}

TEST_CASE("camera models: constructor errors name file:line") {
  test::TempFolder dir;
  const std::string base = "resolution = {64, 48}; pixelSize = {1e-5, 1e-5}; ";
  test::checkBodyError(dir, "c = Camera.ThinLens { " + base + "focalLength = 0.05; focusDistance = 0.5 }\n", 2,
                       "Camera.ThinLens: give exactly one of 'fNumber' (f / aperture diameter) and 'aperture' "
                       "(diameter, metres)");
  test::checkBodyError(dir,
                       "\nc = Camera.ThinLens { " + base +
                           "focalLength = 0.05; focusDistance = 0.5; fNumber = 2; aperture = 0.01 }\n",
                       3,
                       "Camera.ThinLens: give exactly one of 'fNumber' (f / aperture diameter) and 'aperture' "
                       "(diameter, metres)");
  test::checkBodyError(dir, "c = Camera.ThinLens { " + base + "focalLength = 0.05; focusDistance = 0.04; fNumber = 2 }\n",
                       2,
                       "Camera.ThinLens: 'focusDistance' must be > focalLength (metres; a lens cannot focus "
                       "closer than its focal length), got 0.04");
  test::checkBodyError(dir, "c = Camera.ThinLens { " + base + "focalLength = 0.05; focusDistance = 1; fNumber = 0 }\n",
                       2, "Camera.ThinLens: 'fNumber' must be > 0, got 0");
  // cos⁴ vignetting models the chief ray's angle at the sensor; a telecentric lens has none.
  test::checkBodyError(dir,
                       "c = Camera.Orthographic { " + base +
                           "magnification = 1; postProcessing = { Vignetting.Cos4 {} } }\n",
                       2,
                       "Camera.Orthographic: Vignetting.Cos4 (line 2): a telecentric (orthographic) camera's chief rays are "
                       "parallel to the axis, so it has no cos⁴ fall-off; use Vignetting.Radial");
  test::checkBodyError(dir, "c = Camera.Orthographic { " + base + "magnification = -1 }\n", 2,
                       "Camera.Orthographic: 'magnification' must be > 0 (image size / object size), got -1");
  test::checkBodyError(dir, "c = Camera.Orthographic { " + base + "focalLength = 0.01; magnification = 1 }\n", 2,
                       "Camera.Orthographic: unknown key 'focalLength'; valid keys: resolution, principalPoint, "
                       "pixelSize, fillFactor, bitsPerPixel, exposure, distortion, transform, position, lookAt, "
                       "up, sensor, postProcessing, magnification");
  test::checkBodyError(dir, "c = Camera.Orthographic { " + base + "}\n", 2,
                       "Camera.Orthographic: missing required 'magnification'");
  test::checkBodyError(dir, "d = Distortion.Rational { thinPrism = {1, 2, 3} }\n", 2,
                       "Distortion.Rational: 'thinPrism' must be {s1, s2, s3, s4} (4 numbers), got 3 values");
  test::checkBodyError(dir, "d = Distortion.Rational { radial = {1, 2, 3, 4, 5, 6, 7} }\n", 2,
                       "Distortion.Rational: 'radial' must be {k1[, k2[, ..., k6]]} (1 to 6 numbers), got 7 values");
  test::checkBodyError(dir,
                       "local o = Camera.Orthographic { " + base +
                           "magnification = 1 }\nrig = Rig.Stereo { left = o; right = o; baseline = 0.1; "
                           "vergence = 0 }\n",
                       3,
                       "Rig.Stereo: 'left' is a Camera.Orthographic: Rig.Stereo places perspective cameras "
                       "(Pinhole, ThinLens) by their optical centres, which a telecentric camera lacks; give "
                       "each telecentric camera its own transform instead");
}

TEST_CASE("camera models: feature ground truth is what the chief ray hits (thin lens, orthographic)") {
  // A checkerboard seen by a distorted thin lens and by a distorted telecentric camera: every
  // visible feature's image position, traced back through the camera model (its chief ray), meets
  // the target at the feature. Independent of projectToPixel: the ray comes from inverting the
  // distortion by Newton and intersecting the rectangle.
  const std::string cameras[] = {
      "Camera.ThinLens { resolution = {160, 120}; pixelSize = {2e-5, 2e-5}; focalLength = 0.025; "
      "fNumber = 4; focusDistance = 0.35; distortion = Distortion.Rational { radial = {-0.3, 0.1, 0, 0.05}; "
      "thinPrism = {2e-3, 0, -1e-3, 5e-4} } }",
      "Camera.Orthographic { resolution = {160, 120}; pixelSize = {2e-5, 2e-5}; magnification = 0.2; "
      "position = {0, 0, -0.1}; distortion = Distortion.Brown { radial = {-20}; tangential = {0.05, -0.03} } }"};
  for (const std::string& camera : cameras) {
    test::TempFolder dir;
    const PreparedScene ps = prepared(
        dir, "cam = " + camera +
                 "\nboard = Target.Checkerboard { squares = {6, 5}; squareSize = 0.0015; "
                 "location = {-0.004, -0.003, 0.3}; transform = rotate_y(degrees(25)) * rotate_x(degrees(-15)) }\n");
    const std::vector<TargetTruth> truth = targetFeatureTruth(ps, 0);
    REQUIRE(truth.size() == 1);
    int visible = 0;
    for (const FeatureTruth& f : truth[0].features) {
      if (!f.visible()) continue;
      ++visible;
      const CameraRay<double> ray = worldRay(ps.cameras[0].model, f.pixel_px);
      cpu::SurfaceHit hit;
      REQUIRE(cpu::traceNearest(ps, ray.origin, ray.direction, hit));
      // Round trip through the Newton inverse: 1e-13 px ≈ 1e-17 m here; 1e-12 m leaves room.
      CHECK(glm::length(hit.position - f.world_m) < 1e-12);
    }
    CHECK(visible == 20);
  }
}

TEST_CASE("camera orthographic: the flow of a translation is m dX / pixelSize at every depth") {
  // Two plates at 0.1 m and 0.4 m translated by dX = 3e-6 m between frames: a telecentric camera
  // of magnification 0.5 and 1e-5 m pixels sees both move by exactly 0.15 px (a pinhole would see
  // them move by f dX / (Z s), four times less for the far one).
  auto frame = [](const test::TempFolder& dir, int k) {
    const std::string text =
        "cam = Camera.Orthographic { resolution = {40, 30}; pixelSize = {1e-5, 1e-5}; magnification = 0.5; "
        "distortion = Distortion.Brown { radial = {-500} } }\n"
        "near = Object.Simple { shape = Shape.Rectangle { size = {0.0003, 0.0005}; location = {" +
        exactNumber(-0.00017 + k * 3e-6) + ", 0, 0.1} } }\n"
        "far = Object.Simple { shape = Shape.Rectangle { size = {0.0003, 0.0005}; location = {" +
        exactNumber(0.00017 + k * 3e-6) + ", 0, 0.4} } }\n";
    SceneParams params;
    params.frame = k;
    return prepareScene(loadScene(dir.write("scene" + std::to_string(k) + ".lua", text), params));
  };
  test::TempFolder dir;
  const PreparedScene s0 = frame(dir, 0), s1 = frame(dir, 1);
  const RenderResult r0 = renderCpu(s0, 1), r1 = renderCpu(s1, 1);
  const ReferenceFrame reference(0, s0, r0);
  const DerivedTruth t = deriveTruth(reference, 1, s1, r1, 0);
  int near = 0, far = 0;
  for (std::size_t i = 0; i < t.flow_px.size(); ++i) {
    if (r0.cameras[0].objectId[i] == 0) continue;
    (r0.cameras[0].objectId[i] == 1 ? near : far) += 1;
    // With distortion the flow is the distorted image motion: ∂x''/∂x' = 1 + k1 (3x'² + y'²) differs
    // from 1 by at most 3 |k1| r² = 3 · 500 · 1.65e-7 = 2.5e-4 on the plates (r ≤ 0.41 mm), far below
    // the pinhole's factor 4 between the plates.
    CHECK(t.flow_px[i].x == doctest::Approx(0.15).epsilon(3e-4));
    // ∂y''/∂x' = 2 k1 x'y': |flow.y| ≤ (m/s) 2 |k1| |x'| |y'| dX = 5e4 · 2 · 500 · 3.2e-4 · 2.5e-4 · 3e-6
    // = 1.2e-5 px.
    CHECK(std::abs(t.flow_px[i].y) < 1.3e-5);
    CHECK(t.displacement_m[i].x == doctest::Approx(3e-6).epsilon(1e-9));
  }
  CHECK(near > 100);
  CHECK(far > 100);
}

TEST_CASE("camera models: the camera specialization constants change nothing but rounding") {
  // A Brown-distorted pinhole scene (Figure 1) and the thin-lens scene, with
  // the thin-lens, orthographic and rational-distortion code compiled in, render as with it
  // specialized out: the same branches run, and the rational terms with zero coefficients are exact
  // no-ops in the arithmetic (k4..k6 = s1..s4 = 0: a division by 1, additions of 0). The driver's
  // code generation around them may still differ (lavapipe: measured differences of 9e-13 of full
  // scale and 4e-16 m in fp64, 2.7e-4 and 1.5e-7 m in fp32, i.e. rounding), so each precision is
  // held to its own CPU-vs-GPU tolerance, and the thin-lens scene (whose features are all on
  // already, but for the orthographic bit) must not change at all.
  gpu::Renderer renderer(test::gpuContext());
  for (const char* name : {"figure1.lua", "thin_lens.lua"}) {
    const PreparedScene scene = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/" + name, {}), {8});
    PreparedScene compiledIn = scene;
    compiledIn.features.cameraKinds = ~0u;
    compiledIn.features.rationalDistortion = true;
    RenderOptions options;
    options.samplesPerPixel = 4;
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
      INFO(std::string(name) << " " << std::string(toString(p)));
      options.precision = p;
      const RenderResult a = renderer.render(scene, options), b = renderer.render(compiledIn, options);
      const Tolerances tol = tolerancesFor(p);
      const CameraDifference d = compareResults(scene, a, b, tol)[0];
      CHECK(withinTolerance(d, tol));
      CHECK(d.objectIdMismatches == 0);
      if (p == Precision::Fp64) CHECK(d.maxRadianceDiff <= 1e-11);
      if (std::string(name) == "thin_lens.lua") CHECK(a.cameras[0].radiance == b.cameras[0].radiance);
    }
  }
  test::expectNoValidationMessages();
}

TEST_CASE("camera models: a thin-lens stereo rig end to end (EXR header, rig and DICe files)") {
  // Rig.Stereo accepts thin-lens cameras (their chief rays are pinholes with optical centres);
  // the EXR header names the model and its parameters, the rig file and the DICe file carry the
  // rational coefficients in OpenCV's order and under DICe's names.
  test::TempFolder dir;
  const std::string scene = dir.write(
      "rig.lua",
      "local lens = { resolution = {32, 24}; pixelSize = {2e-5, 2e-5}; focalLength = 0.025; fNumber = 4;\n"
      "  focusDistance = 0.4; distortion = Distortion.Rational { radial = {-0.1, 0, 0, 0.02}; thinPrism = {1e-3, 0, 0, 0} } }\n"
      "rig = Rig.Stereo { left = Camera.ThinLens(lens); right = Camera.ThinLens(lens); baseline = 0.1; target = {0, 0, 0.4} }\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.2}; location = {0, 0, 0.4} } }\n");
  const std::string out = dir.file("out");
  const test::CliResult r = test::runCli("render " + scene + " -o " + out + " --backend cpu --spp 1");
  REQUIRE_MESSAGE(r.exitCode == 0, r.err);
  const test::ExrContents exr = test::readExr(out + "/rig.left.exr");
  CHECK(exr.spec.get_string_attribute("dicsynth:camera_model") == "thin_lens");
  CHECK(exr.spec.get_string_attribute("dicsynth:aperture_m") == "0.0062500000000000003");
  CHECK(exr.spec.get_string_attribute("dicsynth:focus_distance_m") == "0.40000000000000002");
  CHECK(exr.spec.get_string_attribute("dicsynth:distortion_coefficients") ==
        "-0.10000000000000001 0 0 0 0 0.02 0 0 0.001 0 0 0");
  // Disparity of the chief rays: every pixel of the left image sees the plate, and the right camera
  // sees most of them.
  REQUIRE(exr.floats.count("disparity.mask"));
  double seen = 0;
  for (float v : exr.floats.at("disparity.mask")) seen += v;
  CHECK(seen > 0.5 * 32 * 24);
  std::ifstream dice(out + "/rig.dice.xml");
  const std::string xml((std::istreambuf_iterator<char>(dice)), std::istreambuf_iterator<char>());
  CHECK(xml.find("name=\"K4\" type=\"double\" value=\"0.02\"") != std::string::npos);
  CHECK(xml.find("name=\"S1\" type=\"double\" value=\"0.001\"") != std::string::npos);
  CHECK(xml.find("OPENCV_LENS_DISTORTION") != std::string::npos);
}
