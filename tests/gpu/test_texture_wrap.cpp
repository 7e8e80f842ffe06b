// Texture.File's `wrap`: a texture that repeats continues across a surface's seams (a tiled
// Shape.Plane's borders, a cylinder's back meridian turned to the camera): the CPU reference's
// image is the periodic spline of the texels (an oracle of dense solves and explicit sums,
// tests/bspline_oracle.h), where the clamped texture breaks; and the GPU renders it as the CPU
// reference does in every precision. The same for Texture.Speckle's `wrap` (an independent oracle
// of the periodic pattern, tests/speckle_oracle.h).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "bspline_oracle.h"
#include "cpu/reference_renderer.h"
#include "every_precision.h"
#include "files/image_io.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "scene/scene.h"
#include "speckle_oracle.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

// The scene at `path`, prepared, and the CPU reference's render of it at 1 spp.
std::pair<PreparedScene, RenderResult> cpuReference(const std::string& path, RenderOptions& options) {
  SceneParams params;
  params.quiet = true;
  PreparedScene scene = prepareScene(loadScene(path, params), {1});
  options.samplesPerPixel = 1;
  RenderResult reference = cpu::render(scene, options);
  return {std::move(scene), std::move(reference)};
}

}  // namespace

TEST_CASE("texture-wrap: a repeating texture has no seam on a tiled plane or around a cylinder, on every renderer") {
  test::TempFolder dir;
  // A 7 × 5 texture of 16-bit noise: each texel spans a few pixels, so a seam would be plain.
  const int w = 7, h = 5;
  std::vector<std::uint16_t> dn(std::size_t(w * h));
  std::vector<double> texels(dn.size());
  for (std::size_t i = 0; i < dn.size(); ++i) {
    dn[i] = std::uint16_t((i * 40503u + 9001u) % 65536u);
    texels[i] = dn[i] / 65535.0;  // the reader's scaling (docs/scene-language.md)
  }
  writeGrayTiff(dir.file("noise.tif"), w, h, dn, 16, "");
  // fillFactor 1e-30: every sample within √1e-30 = 1e-15 px of its pixel's centre, where the
  // reference's uv is; the radiance then differs from the texture at that uv by the slope (~10 per
  // unit uv) × ~1e-15 px × 0.03 uv/px, far below the 1e-9 checked (1e-12 left 1.5e-7).
  const std::string camera =
      "camera = Camera.Pinhole { resolution = {96, 72}; focalLength = 0.01; pixelSize = {1e-5, 1e-5}; fillFactor = 1e-30 }\n";
  struct Case {
    const char* name;
    const char* wrap;
    const char* interpolation;
    std::string object;
  };
  const Case cases[] = {
      // 0.0288 m × 0.0216 m in view at 0.3 m: tile borders at x = ±0.005, ±0.015 m and y = 0, ±0.008 m.
      {"tiled plane, cubic", "repeat", "cubic", "shape = Shape.Plane { tileSize = {0.01, 0.008}; location = {0, 0, 0.3} }"},
      {"tiled plane, quintic", "repeat", "quintic", "shape = Shape.Plane { tileSize = {0.01, 0.008}; location = {0, 0, 0.3} }"},
      // The seam (u = 1 meets u = 0) turned towards the camera, at the image's centre column; v clamped.
      {"cylinder seam, u repeats", "repeatU", "cubic",
       "shape = Shape.Cylinder { radius = 0.01; height = 0.03; capped = false; location = {0, 0, 0.3} }; transform = rotate_y(math.pi)"},
      {"cylinder seam, both repeat", "repeat", "quintic",
       "shape = Shape.Cylinder { radius = 0.01; height = 0.03; capped = false; location = {0, 0, 0.3} }; transform = rotate_y(math.pi)"},
  };
  gpu::Renderer renderer(test::gpuContext());
  for (const Case& c : cases) {
    INFO(std::string(c.name));
    const int degree = std::string(c.interpolation) == "quintic" ? 5 : 3;
    const bool repeatV = std::string(c.wrap) == "repeat";
    const std::vector<double> coefficients = test::splineCoefficients(texels, w, h, degree, true, repeatV);
    // The same texture clamped, for the seam the check must be able to see.
    const std::vector<double> clamped = test::splineCoefficients(texels, w, h, degree, false, false);
    const std::string path = dir.file("scene.lua");
    test::writeBytes(path, camera + "plate = Object.Simple { " + c.object +
                               "; shader = Shader.Constant { color = 1 }; texture = Texture.File { fileName = \"noise.tif\"; "
                               "interpolation = \"" + c.interpolation + "\"; wrap = \"" + c.wrap + "\" } }\n");
    RenderOptions options;
    const auto [scene, reference] = cpuReference(path, options);
    const CameraImage& image = reference.cameras[0];
    int hits = 0, wrong = 0, seamPixels = 0, clampedBreaks = 0;
    double worst = 0;
    for (std::size_t p = 0; p < image.radiance.size(); ++p) {
      if (image.objectId[p] == 0) continue;
      ++hits;
      const dvec2 uv = image.uv[p];
      // uv is in [0, 1]² on these shapes: no coordinate is wrapped or clamped before the spline.
      const double expected = test::splineValue(coefficients, w, h, uv.x, uv.y, degree, true, repeatV);
      const double error = std::abs(image.radiance[p] - expected);
      worst = std::max(worst, error);
      wrong += error > 1e-9;
      // Within a texel of the seam in u: there the clamped texture is another function.
      if (uv.x < 1.0 / w || uv.x > 1 - 1.0 / w) {
        ++seamPixels;
        const double clampedValue = test::splineValue(clamped, w, h, uv.x, uv.y, degree, false, false);
        clampedBreaks += std::abs(clampedValue - expected) > 1e-3;
      }
    }
    MESSAGE(std::string(c.name) << ": " << hits << " hit pixels, worst |Y − periodic spline| " << worst << "; " << clampedBreaks
                   << " of the " << seamPixels << " pixels within a texel of the u seam differ from the clamped texture by > 1e-3");
    CHECK(hits > 1000);
    CHECK(wrong == 0);
    CHECK(seamPixels > 50);
    CHECK(clampedBreaks > seamPixels / 4);  // the check sees a seam where there is one
    test::checkEveryPrecision(renderer, scene, reference, options, false);
  }
  test::expectNoValidationMessages();
}

TEST_CASE("texture-wrap: a periodic Texture.Speckle has no seam on a tiled plane or around a cylinder, on every renderer") {
  test::TempFolder dir;
  // Sample at the pixel centre, where the reference's uv is (fillFactor 1e-30: within 1e-15 px).
  const std::string camera =
      "camera = Camera.Pinhole { resolution = {96, 72}; focalLength = 0.01; pixelSize = {1e-5, 1e-5}; fillFactor = 1e-30 }\n";
  struct Case {
    const char* name;
    double radius, aspect;
    bool repeatU, repeatV;
    std::string object;
  };
  // 0.3 mm per pixel at 0.3 m: disks of ~0.5 mm radius, ~3 px wide cells.
  const Case cases[] = {
      // Tiles 10 × 8 mm: radius 0.047 u = 0.47 mm, 10.6 → 11 cells per tile in u, 8.5 → 9 in v.
      {"tiled plane", 0.047, 0.8, true, true, "shape = Shape.Plane { tileSize = {0.01, 0.008}; location = {0, 0, 0.3} }"},
      // Circumference 62.8 mm, height 30 mm (aspect 0.477): radius 0.0081 u = 0.51 mm, 61.7 → 62 cells
      // around; the seam turned to the camera (centre column).
      {"cylinder seam", 0.0081, 0.03 / (2 * kPi * 0.01), true, false,
       "shape = Shape.Cylinder { radius = 0.01; height = 0.03; capped = false; location = {0, 0, 0.3} }; transform = rotate_y(math.pi)"},
  };
  gpu::Renderer renderer(test::gpuContext());
  for (const Case& c : cases) {
    INFO(std::string(c.name));
    const char* wrap = c.repeatU && c.repeatV ? "repeat" : "repeatU";
    const std::string path = dir.file("scene.lua");
    test::writeBytes(path, camera + "s = Object.Simple { " + c.object + "; shader = Shader.Constant { color = 1 }; " +
                               "texture = Texture.Speckle { radius = " + std::to_string(c.radius) + "; aspect = " +
                               std::to_string(c.aspect) + "; seed = 5; dark = 0.2; light = 0.9; wrap = \"" + wrap + "\" } }\n");
    RenderOptions options;
    const auto [scene, reference] = cpuReference(path, options);
    const CameraImage& image = reference.cameras[0];
    // The oracle from the parameters as written into the scene (std::to_string's 6 decimals).
    const test::SpeckleOracle periodic(std::stod(std::to_string(c.radius)), 0.5, std::stod(std::to_string(c.aspect)), 5,
                                       c.repeatU, c.repeatV);
    test::SpeckleOracle cut = periodic;
    cut.periodU = cut.periodV = 0;
    int hits = 0, wrong = 0, nearRim = 0, seamPixels = 0, cutBreaks = 0;
    for (std::size_t p = 0; p < image.radiance.size(); ++p) {
      if (image.objectId[p] == 0) continue;
      ++hits;
      const dvec2 uv = image.uv[p];
      const long double d2 = periodic.nearestSquared(uv.x, uv.y);
      // uv within ~1e-15 of the sample's: 1e-9 cells² of d² is far beyond any doubt.
      if (std::abs(d2 - 0.25L) < 1e-9L) {
        ++nearRim;
        continue;
      }
      const double expected = d2 <= 0.25L ? 0.2 : 0.9;
      wrong += image.radiance[p] != expected ? 1 : 0;
      // Within a cell of the u seam: the disks there reach across it.
      const double cellU = 1 / double(periodic.cellsU);
      if (uv.x < cellU || uv.x > 1 - cellU) {
        ++seamPixels;
        cutBreaks += (cut.nearestSquared(uv.x, uv.y) <= 0.25L) != (d2 <= 0.25L) ? 1 : 0;
      }
    }
    MESSAGE(std::string(c.name) << ": " << hits << " hit pixels, " << wrong << " differ from the periodic oracle (" << nearRim
                                << " within 1e-9 cells² of a rim); " << cutBreaks << " of the " << seamPixels
                                << " pixels within a cell of the u seam would differ without the modulo");
    CHECK(hits > 1000);
    CHECK(wrong == 0);
    CHECK(seamPixels > 50);
    CHECK(cutBreaks > 0);  // the check sees a seam where there is one
    test::checkEveryPrecision(renderer, scene, reference, options, false);
  }
  test::expectNoValidationMessages();
}
