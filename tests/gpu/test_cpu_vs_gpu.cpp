// Every scene in scenes/ rendered at reduced resolution on the CPU reference and on the GPU
// (lavapipe in CI) with the same samples: fp64 must agree to 1e-9 of full scale and 1e-9 m, df64
// and fp32 within the tolerances derived in host/render/compare.cpp. Also: specialization constants change
// nothing but speed.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "camera/distortion.h"
#include "cpu/reference_renderer.h"
#include "every_precision.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "identical_results.h"
#include "render/compare.h"
#include "scene/scene.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

std::vector<std::string> sceneFiles() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(DS_SOURCE_DIR) + "/scenes"))
    if (e.path().extension() == ".lua") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// Reduced resolution keeps the whole comparison of all scenes within a minute on 2 cores.
constexpr int kDownscale = 4;
// Scenes with NURBS surfaces: the CPU reference finds every root by subdivision (~20 µs per ray),
// so they run at 1/8 of their resolution (200 × 150 for 1600 × 1200) to keep the same budget.
constexpr int kNurbsDownscale = 8;
constexpr int kSpp = 4;

// A scene file's frame 0, prepared at full resolution (or 1/downscale of it), its prints silenced.
PreparedScene prepareQuietly(const std::string& path, int downscale = 1) {
  SceneParams params;
  params.quiet = true;
  return prepareScene(loadScene(path, params), {downscale});
}

// `scene` rendered at 2 spp by the CPU reference and by the GPU in every precision
// (test::checkEveryPrecision).
void checkEveryPrecision(gpu::Renderer& renderer, const PreparedScene& scene, bool sameObjects) {
  RenderOptions options;
  options.samplesPerPixel = 2;
  test::checkEveryPrecision(renderer, scene, cpu::render(scene, options), options, sameObjects);
}

}  // namespace

TEST_CASE("cpu-vs-gpu: every scene in scenes/, fp64 and fp32") {
  const auto files = sceneFiles();
  REQUIRE(files.size() >= 9);
  gpu::Renderer renderer(test::gpuContext());
  for (const std::string& file : files) {
    const Scene loaded = loadScene(file, {});
    bool hasNurbs = false;
    for (const Object& o : loaded.objects) hasNurbs |= o.shape.kind() == ShapeKind::Nurbs;
    const PreparedScene scene = prepareScene(loaded, {hasNurbs ? kNurbsDownscale : kDownscale});
    RenderOptions options;
    options.samplesPerPixel = kSpp;
    options.seed = 3;
    const RenderResult reference = cpu::render(scene, options);
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
      options.precision = p;
      const RenderResult gpu = renderer.render(scene, options);
      const Tolerances tol = tolerancesFor(p);
      for (const CameraDifference& d : compareResults(scene, reference, gpu, tol)) {
        INFO(file << " " << std::string(dicsynth::toString(p)) << " camera " << d.camera);
        MESSAGE(std::filesystem::path(file).filename().string()
                << " " << std::string(dicsynth::toString(p)) << " " << d.camera << ": max dL " << d.maxRadianceDiff << " (" << d.radianceOutliers
                << " px over), max dP " << d.maxPositionDiff_m << " m, max duv " << d.maxUvDiff << ", object mismatches "
                << d.objectIdMismatches << ", geometry outliers " << d.geometryOutliers << " of " << d.pixels << " px, worst error/bound " << d.maxGeometryRatio);
        CHECK(withinTolerance(d, tol));
        if (p == Precision::Fp64) {
          // The requirement, stated directly.
          CHECK(d.maxRadianceDiff <= 1e-9);
          CHECK(d.maxPositionDiff_m <= 1e-9);
          CHECK(d.maxNormalDiff <= 1e-9);  // unit normals, computed in double on both sides
          CHECK(d.objectIdMismatches == 0);
        }
      }
    }
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: df64's differences at other seeds are samples on the other side of an edge, the geometry intact") {
  // The audit of 2026-11-27 ran compare with other seeds and found df64 over its radiance bound on
  // single pixels, against the documented "none": shadows.lua and telecentric.lua at seed 3 (a
  // sample on the other side of an object's edge) and plate_hole.lua at seed 4 (a sample by the
  // ring's seam, u = 0 ≡ 1, given the other side's texture). df64's search decides hit or miss in
  // float (host/render/compare.cpp), so the rule is fp32's: flips at object edges, at most 1e-4 of
  // the pixels elsewhere, while every pixel-centre ray keeps its df64 bound.
  gpu::Renderer renderer(test::gpuContext());
  struct Case {
    const char* scene;
    std::uint32_t seed;
  };
  for (const Case& c : {Case{"shadows.lua", 3}, Case{"telecentric.lua", 3}, Case{"plate_hole.lua", 4}}) {
    const PreparedScene scene = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/" + c.scene, {}), {kDownscale});
    RenderOptions options;
    options.samplesPerPixel = 2;
    options.seed = c.seed;
    const RenderResult reference = cpu::render(scene, options);
    options.precision = Precision::Df64;
    const Tolerances tol = tolerancesFor(Precision::Df64);
    for (const CameraDifference& d : compareResults(scene, reference, renderer.render(scene, options), tol)) {
      INFO(std::string(c.scene) << " seed " << c.seed);
      MESSAGE(std::string(c.scene) << " df64 seed " << c.seed << ": " << d.radianceOutliers << " px over the radiance bound ("
                      << d.radianceOutliersOffEdge << " off edges), max dL " << d.maxRadianceDiff);
      CHECK(withinTolerance(d, tol));
      CHECK(d.geometryOutliers == 0);      // pixel centres: P and uv within the df64 bound
      CHECK(d.objectIdMismatches == 0);    // and the same object
      CHECK(d.wrongNearestHits() == 0);
    }
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: the randomized campaign's cases within the bounds that now cover them") {
  // A campaign of 153 random analytic scenes (2026-11-27) found valid scenes that compare failed
  // with identical or explained pixels, each because a bound missed a term (host/render/compare.cpp,
  // render/shading_tolerance.h). Reduced by the campaign, they must now pass, and each still shows
  // the effect its term covers (so the case cannot pass vacuously).
  test::TempFolder dir;
  std::filesystem::copy_file(std::string(DS_SOURCE_DIR) + "/scenes/speckle.tif", dir.file("speckle.tif"));
  gpu::Renderer renderer(test::gpuContext());
  struct Case {
    const char* name;
    Precision precision;
    int spp;
    std::uint32_t seed;
    const char* text;
  };
  const char* overexposed =
      "camera = Camera.Pinhole { resolution = {128, 96}; pixelSize = {5e-06, 5e-06}; focalLength = 0.02; exposure = 20 }\n"
      "floor = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.2}; location = {0, 0, 0.5} }; shader = Shader.Lambert { color = 0.5 } }\n"
      "lamp = Light.Point { position = {0.0, 0.0, 0.2}; intensity = 1 }\n";
  const Case cases[] = {
      // Up to 35 times full scale: float shading errs relative to the value (r0 scaled by it).
      {"overexposed", Precision::Df64, 2, 4, overexposed},
      // A lamp 0.5 mm from a plate 2 m away: the float vector to the light errs by ε·2 m over r.
      {"lamp near the surface", Precision::Df64, 2, 4,
       "camera = Camera.Pinhole { resolution = {128, 96}; pixelSize = {5e-06, 5e-06}; focalLength = 0.2 }\n"
       "floor = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.2}; location = {0, 0, 2} }; shader = Shader.Lambert { color = 0.5 } }\n"
       "lamp = Light.Point { position = {0.0, 0.0, 2 - 0.0005}; intensity = 0.0000015 }\n"},
      // A fine speckle on a 96×72 image: a sample's flip at a dot's edge is an allowed outlier
      // (floor(1e-4 × 6912) allowed none; the Poisson allowance is 7).
      {"small speckle image", Precision::Fp32, 4, 3,
       "camera = Camera.Pinhole { resolution = {96, 72}; pixelSize = {5e-06, 5e-06}; focalLength = 0.01 }\n"
       "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.2}; location = {0, 0, 0.5} }; shader = Shader.Constant { color = 1 }; "
       "texture = Texture.Speckle { radius = 0.002; seed = 7 } }\n"},
      // A defocused rectangle (blur radius ~4 px): samples cross its silhouette from pixels up to the
      // blur radius away, which count as edge pixels.
      {"defocused silhouette", Precision::Fp32, 2, 6,
       "camera = Camera.ThinLens { resolution = {80, 60}; pixelSize = {3.45e-06, 3.45e-06}; focalLength = 0.02308100462286311; "
       "focusDistance = 0.5579324045036034; fNumber = 12.766975888537818; position = {0.08, 0.175, -0.05}; "
       "lookAt = {-0.0626303498163909, 0.19267816884625089, 0.6328088544990466} }\n"
       "obj0 = Object.Simple { shape = Shape.Rectangle { size = {0.002320875328821244, 0.0053887535850182565}; "
       "location = {-0.05975805362641453, 0.1915820839713709, 0.6317045037784011} }; shader = Shader.Constant { color = 0.5482347722148027 }; "
       "texture = Texture.File { fileName = \"speckle.tif\"; interpolation = \"cubic\" }; "
       "transform = rotate_z(3.141592653589793) * rotate_y(-0.6440493403798633) }\n"},
  };
  for (const Case& c : cases) {
    INFO(std::string(c.name));
    const std::string path = dir.file(std::string("case_") + std::to_string(&c - cases) + ".lua");
    test::writeBytes(path, c.text);
    const PreparedScene scene = prepareQuietly(path);
    RenderOptions options;
    options.samplesPerPixel = c.spp;
    options.seed = c.seed;
    const RenderResult reference = cpu::render(scene, options);
    options.precision = c.precision;
    const Tolerances tol = tolerancesFor(c.precision);
    for (const CameraDifference& d : compareResults(scene, reference, renderer.render(scene, options), tol)) {
      MESSAGE(std::string(c.name) << ": max dL " << d.maxRadianceDiff << " of full scale, " << d.radianceOutliers << " px over ("
                     << d.radianceOutliersOffEdge << " off edges, " << allowedOutliers(tol, d.pixels) << " allowed)");
      CHECK(withinTolerance(d, tol));
      CHECK(d.wrongNearestHits() == 0);
      if (std::string(c.name) == "overexposed" || std::string(c.name) == "lamp near the surface")
        CHECK(d.maxRadianceDiff > tol.radiance);  // the fixed part alone did not cover them
      if (std::string(c.name) == "defocused silhouette") CHECK(d.radianceOutliers > 0);  // all by the silhouette
    }
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: distortions whose corners Newton from the pixel cannot invert agree in every precision") {
  // The camera audit of 2026-11-28's two reproductions, refused before as "folds over inside the
  // image" though neither folds there: Rational k4 = -4.2 alone (r'' = r/(1 - 4.2 r²) increases up
  // to its pole at r = 0.488, the corner's root is at 0.305) and Brown {6, -20} (increasing up to
  // its fold at r = 0.474, the corner's root at 0.349). Newton from the corner starts beyond the
  // pole or fold and fails; the path from the centre (camera/distortion.h, and its GLSL twin) finds
  // the root on both backends. fx = 500 px: the sensitive area's corner is at r'' = 0.5.
  test::TempFolder dir;
  gpu::Renderer renderer(test::gpuContext());
  const char* distortions[] = {"Distortion.Rational { radial = {0, 0, 0, -4.2, 0, 0} }",
                               "Distortion.Brown { radial = {6, -20, 0} }"};
  for (const char* distortion : distortions) {
    INFO(distortion);
    const std::string path = dir.file("path.lua");
    test::writeBytes(path, std::string("camera = Camera.Pinhole { resolution = {400, 300}; pixelSize = {1e-5, 1e-5}; focalLength = 0.005;\n"
                                       "  distortion = ") + distortion + " }\n"
                                       "plate = Object.Simple { shape = Shape.Rectangle { size = {4, 3}; location = {0, 0, 1} };\n"
                                       "  shader = Shader.Constant { color = 1 }; texture = Texture.Speckle { radius = 0.01; seed = 3 } }\n");
    const PreparedScene scene = prepareQuietly(path, 4);  // 100 x 75 px, fx = 125 px
    const auto& m = scene.cameras[0].model;
    const dvec2 corner{(-0.5 - m.cx) / m.fx, (-0.5 - m.cy) / m.fy};
    glm::dvec2 newton;
    REQUIRE_FALSE(undistortNewton(m.brown, corner, corner, newton));  // the case the path is for
    // Every pixel centre sees the plate on both: none lost to a failed inversion.
    checkEveryPrecision(renderer, scene, true);
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: a point light nearly 1e12 m away lights and shadows alike in every precision") {
  // A far point light stands in for a directional one; up to 1e12 m from the origin it is accepted
  // (Light.Point's limit: beyond it the fp32 path's r² and intensity near float's range). Refused
  // before at 1e12 m for an untransformed plate (prepare's homography test; the radiometry audit of
  // 2026-11-28). Here 9.4e11 m, oblique, a sphere's shadow on a Lambert plate: the compare rules
  // of every precision hold, shadow edges included.
  test::TempFolder dir;
  gpu::Renderer renderer(test::gpuContext());
  const std::string path = dir.file("sun.lua");
  test::writeBytes(path, "camera = Camera.Pinhole { resolution = {400, 300}; pixelSize = {1e-5, 1e-5}; focalLength = 0.005 }\n"
                         "plate = Object.Simple { shape = Shape.Rectangle { size = {4, 3}; location = {0, 0, 1} };\n"
                         "  shader = Shader.Lambert { color = 0.8 }; texture = Texture.Speckle { radius = 0.01; seed = 3 } }\n"
                         "ball = Object.Simple { shape = Shape.Sphere { radius = 0.2; location = {0, 0, 0.7} };\n"
                         "  shader = Shader.Lambert { color = 0.5 } }\n"
                         "sun = Light.Point { position = {3e11, -4e11, -8e11}; intensity = 1e24 }\n");
  // 100 x 75 px; the sphere's silhouette pixels follow each precision's edge rules (withinTolerance).
  checkEveryPrecision(renderer, prepareQuietly(path, 4), false);
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: objects far from the world origin agree in every precision (5,000 and 20,000 km out)") {
  // Map-grid coordinates: scenes placed 5e6 to 2e7 m from the world origin. Both paths used to map
  // world points into an object as A⁻¹p − A⁻¹b, losing ~1e-16 of the distance from the origin
  // before the cancellation, and the CPU shaded from the world hit point, which carries the same
  // rounding: the 1 mm sphere seen from 5 mm below failed compare in every precision (fp64: 1208
  // geometry outliers; the shape audit of 2026-11-28), the lit sphere and plate 0.3 m away failed
  // fp64 (radiance 2e-9 of full scale) and df64. The maps are now taken relative to each object's
  // origin (geometry/object_map.h) and the CPU shades relative to the ray's origin, as the GPU
  // does: every precision holds its rules, with no wrong nearest hit.
  test::TempFolder dir;
  gpu::Renderer renderer(test::gpuContext());
  const std::string small = dir.file("mm.lua");
  test::writeBytes(small,
                   "camera = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.00096; pixelSize = {1e-5, 1e-5};\n"
                   "  position = {5e6, -3.5e6, 1499999.995}; lookAt = {5e6, -3.5e6, 1.5e6}; up = {0, -1, 0} }\n"
                   "ball = Object.Simple { shape = Shape.Sphere { radius = 0.001; location = {5e6, -3.5e6, 1.5e6} };\n"
                   "  texture = Texture.Speckle { radius = 0.0001; seed = 2 }; transform = rotate_x(0.4) * rotate_y(1.1) }\n");
  checkEveryPrecision(renderer, prepareQuietly(small), true);
  const std::string lit = dir.file("lit.lua");
  test::writeBytes(lit,
                   "local function at(x, y, z) return {1.6e7 + x, -1.05e7 + y, 3.5e6 + z} end\n"
                   "camera = Camera.Pinhole { resolution = {96, 72}; focalLength = 0.012; pixelSize = {1e-5, 1e-5};\n"
                   "  position = at(0, -0.02, -0.3); lookAt = at(0, 0, 0); up = {0, -1, 0} }\n"
                   "lamp = Light.Point { position = at(0.1, -0.2, -0.15); intensity = 0.05 }\n"
                   "ball = Object.Simple { shape = Shape.Sphere { radius = 0.02; location = at(0, 0, -0.03) };\n"
                   "  shader = Shader.Lambert {}; texture = Texture.Speckle { seed = 3; radius = 0.002 };\n"
                   "  transform = rotate_x(0.4) * rotate_y(1.1) }\n"
                   "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = at(0, 0, 0) };\n"
                   "  shader = Shader.Phong { shininess = 20 }; texture = Texture.Speckle { seed = 4; radius = 0.002 };\n"
                   "  transform = rotate_y(0.3) }\n");
  checkEveryPrecision(renderer, prepareQuietly(lit), false);
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: shadow rays leaving a NURBS surface do not block themselves") {
  // A flat NURBS plate of 128 × 128 spans (patches of 0.8 mm at 0.4 m) lit at cos 0.11: every pixel
  // is lit (a plane cannot shadow itself). A shadow ray's origin, rounded into the float search,
  // lies off the surface by its rounding, and the surface's own root there lay beyond the patch-
  // parameter window that identified it: df64 blocked all 12,288 shadow rays, fp32 2,485 (a
  // randomized campaign of 2026-11-28; shaders/lib/nurbs.glsl, ds_search_nurbs).
  test::TempFolder dir;
  const std::string path = dir.write(
      "plate.lua",
      "camera = Camera.Pinhole { resolution = {128, 96}; pixelSize = {1e-5, 1e-5}; focalLength = 0.01 }\n"
      "plate = Object.Simple { shape = Nurbs.plate { size = {0.1, 0.075}; spans = {128, 128}; location = {0, 0, 0.4} }; "
      "shader = Shader.Lambert { color = 0.5 } }\n"
      "lamp = Light.Point { position = {-0.3, -0.01, 0.37}; intensity = 1.2 }\n");
  const PreparedScene scene = prepareQuietly(path);
  REQUIRE(scene.objects[0].nurbs);
  CHECK_FALSE(scene.objects[0].nurbs->closedU);  // an open plate: its borders are edges, no seam
  CHECK_FALSE(scene.objects[0].nurbs->closedV);
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = 1;
  options.seed = 3;
  const RenderResult reference = cpu::render(scene, options);
  const std::vector<double>& lit = reference.cameras[0].radiance;
  CHECK(std::all_of(lit.begin(), lit.end(), [](double L) { return L > 0.1; }));  // the reference: all lit
  for (Precision precision : {Precision::Fp32, Precision::Df64, Precision::Fp64}) {
    INFO(toString(precision));
    options.precision = precision;
    const Tolerances tol = tolerancesFor(precision);
    for (const CameraDifference& d : compareResults(scene, reference, renderer.render(scene, options), tol)) {
      CHECK(d.radianceOutliers == 0);  // no shadow edge: no flip is explained
      CHECK(withinTolerance(d, tol));
      CHECK(d.wrongNearestHits() == 0);
    }
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: a closed NURBS surface's seam is no edge: df64 keeps the near root on it") {
  // A Nurbs.from sphere under a projective map puts pixel (43, 7)'s centre 1.4e-6 from the seam
  // u = 0 ≡ 1 (a randomized campaign of 2026-11-28, reduced). The seam was judged as the surface's
  // edge: df64 refined the copy of the root found beyond u = 1, rejected it, and resumed the search
  // strictly beyond its s, past the u = 0 patch's copy of the same float s, to the sphere's far side
  // (4 cm behind; compare passed it on the silhouette's allowance). Held here: no wrong hit at all.
  test::TempFolder dir;
  const std::string path = dir.write(
      "seam.lua",
      "camera = Camera.ThinLens { resolution = {64, 48}; pixelSize = {1e-5, 1e-5}; focalLength = 0.0009059474649181499; "
      "focusDistance = 0.35601879937795594; fNumber = 4; position = {-0.08212461589818953, -0.1456847981960661, "
      "0.044592375018525074}; lookAt = {-0.0015740714665520667, -0.004860128572368252, 0.3681204340419068} }\n"
      "ball = Object.Simple { shape = Nurbs.from { shape = Shape.Sphere { radius = 0.07512119120066896; location = "
      "{-0.015514914499333302 - 0.0006341054195759422, -0.024332317725080432 + 0.0006749471838362875, "
      "0.39233913314457114 - 0.0004863266911118126} } }; shader = Shader.Constant { color = 0.63 }; transform = "
      "homography {1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -0.27817563267333556, "
      "1.5934967466693206, -0.6263091145869628, 1.0} * rotate_x(1.1186532503801425) * rotate_y(1.1183499448969727) "
      "* rotate_z(-0.013507742098785695) }\n");
  const PreparedScene scene = prepareQuietly(path);
  REQUIRE(scene.objects[0].nurbs);
  CHECK(scene.objects[0].nurbs->closedU);        // the ring's seam
  CHECK_FALSE(scene.objects[0].nurbs->closedV);  // poles, not a seam
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = 2;
  options.seed = 6772;
  const RenderResult reference = cpu::render(scene, options);
  CHECK(reference.cameras[0].uv[7 * 64 + 43].x < 1e-5);  // that pixel centre sees the seam
  for (Precision precision : {Precision::Fp32, Precision::Df64, Precision::Fp64}) {
    INFO(toString(precision));
    options.precision = precision;
    const Tolerances tol = tolerancesFor(precision);
    const RenderResult gpu = renderer.render(scene, options);
    for (const CameraDifference& d : compareResults(scene, reference, gpu, tol)) {
      CHECK(withinTolerance(d, tol));
      CHECK(d.wrongNearestHits() == 0);
    }
    const dvec2 uv = gpu.cameras[0].uv[7 * 64 + 43];
    CHECK(uv.x >= 0);  // on the seam (either side names it), within [0, 1]
    CHECK(uv.x <= 1);
    CHECK(std::min(uv.x, 1 - uv.x) < 1e-5);
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: a fitted closed surface, seen along its seam, agrees in fp64 (plate_hole.lua, frame 1)") {
  // At 1/8 size the image's middle row lies on the ring's seam (u = 0 ≡ 1). Fitted apart, the seam
  // of frame 1's Nurbs.deform overlapped by ~1e-7 in u, the CPU and the GPU took either side, and
  // |Δuv| reached 1.1e-7 against fp64's 1e-9 (audit of 2026-11-27). The fit now keeps the seam
  // closed (nurbs/nurbs_fit.cpp), so either side is the same point and (u, v) up to the period.
  gpu::Renderer renderer(test::gpuContext());
  SceneParams params;
  params.frame = 1;
  params.quiet = true;
  const PreparedScene scene =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/plate_hole.lua", params), {kNurbsDownscale});
  RenderOptions options;
  options.samplesPerPixel = 1;
  options.frame = 1;
  const RenderResult reference = cpu::render(scene, options);
  options.precision = Precision::Fp64;
  const Tolerances tol = tolerancesFor(Precision::Fp64);
  for (const CameraDifference& d : compareResults(scene, reference, renderer.render(scene, options), tol)) {
    MESSAGE("plate_hole frame 1 fp64: max duv " << d.maxUvDiff << ", max dP " << d.maxPositionDiff_m << " m");
    CHECK(withinTolerance(d, tol));
    CHECK(d.maxUvDiff <= 1e-9);
  }
  test::expectNoValidationMessages();
}

TEST_CASE("cpu-vs-gpu: switching features off by specialization changes no pixel") {
  const PreparedScene scene =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/rectangle.lua", {}), {kDownscale});
  REQUIRE_FALSE(scene.features.lights);
  REQUIRE_FALSE(scene.features.distortion);
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = kSpp;
  for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
    options.precision = p;
    const RenderResult specialized = renderer.render(scene, options, {true});
    const RenderResult general = renderer.render(scene, options, {false});
    // Identical arithmetic on the paths that run; only dead code differs. The specialized pipeline
    // of this scene without NURBS is also made from the module compiled without the NURBS search
    // (gpu::renderSpirv), the general one from the module with it.
    test::checkSameArithmetic(scene, general, specialized, p);
  }
  test::expectNoValidationMessages();
}

// --layers without image, radiance, noise or defects (RenderOptions::radiance false): no sample
// ray is traced, only the pixel-centre ground-truth ray, whose results are those of a full render.
TEST_CASE("cpu-vs-gpu: without a radiance layer only the ground-truth ray is traced, with a full render's results") {
  // figure1: a file texture, distortion and lights (the sample path's features); dogbone: NURBS.
  for (const char* name : {"figure1.lua", "dogbone.lua"}) {
    INFO(name);
    const PreparedScene scene = prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/" + name, {}), {kNurbsDownscale});
    gpu::Renderer renderer(test::gpuContext());
    RenderOptions full;
    full.samplesPerPixel = kSpp;
    RenderOptions truthOnly = full;
    truthOnly.radiance = false;
    for (Precision p : {Precision::Fp64, Precision::Df64, Precision::Fp32}) {
      INFO(toString(p));
      full.precision = truthOnly.precision = p;
      const RenderResult a = renderer.render(scene, full), b = renderer.render(scene, truthOnly);
      RenderResult withRadiance = b;  // radiance is 0 everywhere; the rest must be a's bits
      for (std::size_t c = 0; c < b.cameras.size(); ++c) {
        const std::vector<double>& radiance = b.cameras[c].radiance;
        CHECK(std::all_of(radiance.begin(), radiance.end(), [](double r) { return r == 0.0; }));
        withRadiance.cameras[c].radiance = a.cameras[c].radiance;
      }
      test::checkSameArithmetic(scene, a, withRadiance, p);
    }
    RenderResult cpuTruth = cpu::render(scene, truthOnly);
    const RenderResult cpuFull = cpu::render(scene, full);
    for (std::size_t c = 0; c < cpuTruth.cameras.size(); ++c) {
      const std::vector<double>& radiance = cpuTruth.cameras[c].radiance;
      CHECK(std::all_of(radiance.begin(), radiance.end(), [](double r) { return r == 0.0; }));
      cpuTruth.cameras[c].radiance = cpuFull.cameras[c].radiance;
    }
    test::checkIdenticalResults(scene, cpuFull, cpuTruth);
  }
  test::expectNoValidationMessages();
}

TEST_CASE("compare: wrong nearest hits are counted by kind") {
  // A reference render compared with a copy altered on five chosen pixels, one per kind: each must
  // land in its own count, and nothing else may. The alterations are far beyond any bound (1 cm on
  // a plate 0.3 m away, where fp32's position bound is ~1e-6 m).
  const PreparedScene scene =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/nurbs_plate.lua", {}), {16});
  RenderOptions options;
  options.samplesPerPixel = 1;
  const RenderResult reference = cpu::render(scene, options);
  RenderResult altered = reference;
  CameraImage& image = altered.cameras[0];
  std::vector<std::size_t> hits, misses;
  for (std::size_t i = 0; i < image.pixelCount(); ++i) (image.objectId[i] != 0 ? hits : misses).push_back(i);
  REQUIRE(hits.size() >= 5);
  REQUIRE(!misses.empty());
  const Camera& cam = scene.cameras[0].camera;
  const dvec3 centre = scene.cameras[0].model.centre;
  auto moveAlongRay = [&](std::size_t i, double by_m) {
    const double distance = glm::length(image.position_m[i] - centre);
    image.position_m[i] += by_m / distance * (image.position_m[i] - centre);
    image.depth_m[i] *= (distance + by_m) / distance;  // along a ray from the centre, depth ∝ distance
  };
  image.objectId[hits[0]] = 0;  // miss
  image.objectId[misses[0]] = 1;  // extra hit
  image.position_m[misses[0]] = dvec3(0, 0, 0.3);
  image.objectId[hits[1]] = 99;  // other object, in front
  moveAlongRay(hits[1], -0.01);
  moveAlongRay(hits[2], 0.01);   // farther root
  moveAlongRay(hits[3], -0.01);  // nearer root
  // Another object at the same point: a tie at an edge pixel (an edge two objects share), a wrong
  // hit away from edges. The plate's first pixel in raster order has background above it; the
  // interior pixel has the plate all around (compare's edge map: the 8 neighbours, for a pinhole).
  const long width = image.width_px;
  const auto interior = std::find_if(hits.begin(), hits.end(), [&](std::size_t i) {
    const long x = long(i) % width, y = long(i) / width;
    if (x == 0 || y == 0 || x + 1 >= width || y + 1 >= image.height_px) return false;
    for (long dy = -1; dy <= 1; ++dy)
      for (long dx = -1; dx <= 1; ++dx)
        if (reference.cameras[0].objectId[std::size_t((y + dy) * width + x + dx)] != 1) return false;
    return true;
  });
  REQUIRE(interior != hits.end());
  REQUIRE(*interior > hits[4]);
  image.objectId[hits[4]] = 99;    // a tie
  image.objectId[*interior] = 99;  // a wrong hit
  INFO("camera " << cam.name);
  for (const Precision p : {Precision::Fp64, Precision::Fp32}) {
    const std::vector<CameraDifference> d = compareResults(scene, reference, altered, tolerancesFor(p));
    REQUIRE(d.size() == 1);
    CHECK(d[0].wrongMiss == 1);
    CHECK(d[0].wrongExtraHit == 1);
    CHECK(d[0].wrongOtherObject == 2);  // in front, and at the same point away from edges
    CHECK(d[0].wrongFartherRoot == 1);
    CHECK(d[0].wrongNearerRoot == 1);
    CHECK(d[0].wrongNearestHits() == 6);
    CHECK(d[0].objectTies == 1);  // not a wrong hit, nor a mismatch
    CHECK(d[0].objectIdMismatches == 4);  // miss, extra hit, the two other objects
    CHECK(*layerDifference(d[0], Layer::Mask) == 5.0);  // the objectId layer differs at the tie too
    // The unaltered comparison counts none.
    CHECK(compareResults(scene, reference, reference, tolerancesFor(p))[0].wrongNearestHits() == 0);
  }
}
