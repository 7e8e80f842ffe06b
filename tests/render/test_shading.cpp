// Reflectance models (host/reflectance) and lights (host/cpu/shading.h) against closed forms
// computed here from angles, independently of the vector code; ambient and several lights on whole
// renders; every registered model from the scene language; the constructors' errors. The GPU
// twins: tests/gpu/test_shading_gpu.cpp and test_cpu_vs_gpu.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "cpu/reference_renderer.h"
#include "cpu/shading.h"
#include "reflectance/registry.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;
using dicsynth::test::checkBodyError;
using dicsynth::test::kCameraLine;
using dicsynth::test::TempFolder;

namespace {

// Unit vector at polar angle θ from +z, azimuth φ from +x.
dvec3 polar(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// An object of the given reflectance model (its home's parameters).
PreparedObject material(reflectance::Model model) {
  PreparedObject o;
  o.shader = model;
  return o;
}
reflectance::Phong phong(double ks, int n) { return {{ks, n}}; }
reflectance::BlinnPhong blinnPhong(double ks, int n) { return {{ks, n}}; }
reflectance::Ggx ggx(double alpha, double f0) {
  reflectance::Ggx g;
  g.roughness = alpha;
  g.f0 = f0;
  return g;
}

constexpr double kDeg = kPi / 180;
const dvec3 kNormal{0, 0, 1};

// Trapezoid-free composite Simpson of f over [a, b] with n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return sum * h / 3;
}

}  // namespace

TEST_CASE("shading: Phong peak at the mirror direction and its value off the peak") {
  const PreparedObject o = material(phong(0.3, 40));
  const double peak = 0.3 * 42 / (2 * kPi);
  // Light 30° from the normal at azimuth 0; its mirror direction is 30° at azimuth 180°.
  const dvec3 wi = polar(30 * kDeg, 0);
  CHECK(cpu::specularBrdf(o, kNormal, wi, polar(30 * kDeg, kPi)) == doctest::Approx(peak).epsilon(1e-14));
  // The viewer 10° further from the normal than the mirror direction: α = 10°.
  CHECK(cpu::specularBrdf(o, kNormal, wi, polar(40 * kDeg, kPi)) ==
        doctest::Approx(peak * std::pow(std::cos(10 * kDeg), 40)).epsilon(1e-12));
  // Out of the plane of incidence: the angle between two unit vectors by the spherical law of
  // cosines, cos α = cos θ1 cos θ2 + sin θ1 sin θ2 cos Δφ.
  const double cosAlpha = std::cos(30 * kDeg) * std::cos(35 * kDeg) + std::sin(30 * kDeg) * std::sin(35 * kDeg) * std::cos(20 * kDeg);
  CHECK(cpu::specularBrdf(o, kNormal, wi, polar(35 * kDeg, kPi + 20 * kDeg)) ==
        doctest::Approx(peak * std::pow(cosAlpha, 40)).epsilon(1e-12));
  // Beyond 90° from the mirror direction the lobe is 0.
  CHECK(cpu::specularBrdf(o, kNormal, polar(80 * kDeg, 0), polar(80 * kDeg, 0)) == 0.0);
}

TEST_CASE("shading: Blinn-Phong peak when the half vector is the normal, and off the peak") {
  const PreparedObject o = material(blinnPhong(0.25, 100));
  const double peak = 0.25 * 108 / (8 * kPi);
  CHECK(cpu::specularBrdf(o, kNormal, polar(25 * kDeg, 0), polar(25 * kDeg, kPi)) == doctest::Approx(peak).epsilon(1e-14));
  // Light at 30°, viewer at 50° on the other side, in one plane: the half vector is 10° off.
  CHECK(cpu::specularBrdf(o, kNormal, polar(30 * kDeg, 0), polar(50 * kDeg, kPi)) ==
        doctest::Approx(peak * std::pow(std::cos(10 * kDeg), 100)).epsilon(1e-12));
}

TEST_CASE("shading: Phong's normalization gives albedo ks for a viewer on the normal") {
  // With V = N the lobe's angle α is θi, so ∫ f_spec cosθi dωi = ks (n+2)/(2π) 2π ∫ cos^(n+1)θ sinθ dθ.
  for (int n : {1, 10, 200}) {
    const PreparedObject o = material(phong(0.4, n));
    const double albedo = simpson([&](double t) { return cpu::specularBrdf(o, kNormal, polar(t, 0), kNormal) *
                                                         std::cos(t) * std::sin(t) * 2 * kPi; },
                                  0, kPi / 2, 20000);
    CHECK(albedo == doctest::Approx(0.4).epsilon(1e-8));  // Simpson's error ~h⁴ n⁴: < 1e-10 here
  }
}

TEST_CASE("shading: GGX distribution is normalized, ∫ D cosθh dω = 1") {
  for (double alpha : {0.02, 0.1, 0.3, 0.7, 1.0}) {
    // μ = cos θh: ∫ D cosθh dω = 2π ∫₀¹ D(μ) μ dμ; D has width ~α² in μ near 1, so the grid is
    // fine there (μ = 1 − s², s uniform: dμ = 2s ds).
    const double integral = simpson([&](double s) {
      const double mu = 1 - s * s;
      return 2 * kPi * reflectance::Ggx::distribution(alpha, mu, s * s * (1 + mu)) * mu * 2 * s;  // 1 − μ² = s²(1 + μ)
    }, 0, 1, 200000);
    CHECK(integral == doctest::Approx(1).epsilon(1e-7));
  }
}

TEST_CASE("shading: GGX at normal incidence and its Smith term against the tan form") {
  const double alpha = 0.3, f0 = 0.9;
  const PreparedObject o = material(ggx(alpha, f0));
  // Light and viewer on the normal: D = 1/(πα²), F = F0, G₂ = 1, f = D F G₂ / 4.
  CHECK(cpu::specularBrdf(o, kNormal, kNormal, kNormal) == doctest::Approx(f0 / (kPi * alpha * alpha) / 4).epsilon(1e-14));
  // G₂ = 1/(1 + Λi + Λo), Λ(θ) = (√(1 + α² tan²θ) − 1)/2 (Heitz 2014), against the algebraic form.
  const auto lambda = [&](double theta) { return (std::sqrt(1 + alpha * alpha * std::pow(std::tan(theta), 2)) - 1) / 2; };
  for (double ti : {5.0, 40.0, 80.0})
    for (double to : {0.0, 30.0, 70.0, 89.0}) {
      const double g2 = 1 / (1 + lambda(ti * kDeg) + lambda(to * kDeg));
      CHECK(reflectance::Ggx::visibility(alpha, std::cos(ti * kDeg), std::cos(to * kDeg)) ==
            doctest::Approx(g2 / (4 * std::cos(ti * kDeg) * std::cos(to * kDeg))).epsilon(1e-12));
    }
  // Schlick: F0 at 0°, 1 at grazing, F0 + (1 − F0)/32 at 60° (1 − cos 60° = 1/2).
  CHECK(reflectance::Ggx::fresnel(f0, 1) == f0);
  CHECK(reflectance::Ggx::fresnel(f0, 0) == 1);
  CHECK(reflectance::Ggx::fresnel(f0, 0.5) == doctest::Approx(f0 + (1 - f0) / 32).epsilon(1e-15));
}

TEST_CASE("shading: GGX white furnace against an independent integral over half vectors") {
  // F0 = 1, viewer on the normal: E = ∫ f cosθi dωi ≤ 1 (single scattering loses the energy that
  // leaves below the horizon or is masked). Independently: sample the half vector by the inverse
  // CDF of D cosθh, θh(ξ) = atan(α √(ξ/(1 − ξ))); with ωo = n the change of variables leaves
  // E = ∫₀¹ G₂(θi = 2θh, θo = 0) [2θh < π/2] dξ, G₂ from the tan form of Λ (not the code's).
  for (double alpha : {0.05, 0.3, 0.8}) {
    const PreparedObject o = material(ggx(alpha, 1.0));
    const double e = simpson([&](double t) { return cpu::specularBrdf(o, kNormal, polar(t, 0), kNormal) *
                                                    std::cos(t) * std::sin(t) * 2 * kPi; },
                             0, kPi / 2 - 1e-9, 400000);
    const int n = 400000;
    double reference = 0;
    for (int i = 0; i < n; ++i) {
      const double xi = (i + 0.5) / n, thetaI = 2 * std::atan(alpha * std::sqrt(xi / (1 - xi)));
      if (thetaI >= kPi / 2) continue;
      reference += 1 / (1 + (std::sqrt(1 + alpha * alpha * std::pow(std::tan(thetaI), 2)) - 1) / 2);
    }
    reference /= n;
    MESSAGE("GGX directional albedo at alpha " << alpha << ": " << e << ", independent " << reference);
    CHECK(e <= 1);
    // The midpoint rule over ξ errs by ~1/n at the horizon's cut-off: 2.5e-6; Simpson far less.
    CHECK(e == doctest::Approx(reference).epsilon(1e-5));
  }
}

TEST_CASE("shading: spot light is full inside the inner cone, dark outside the outer, smooth between") {
  PreparedLight spot;
  spot.kind = LightKind::Spot;
  spot.position_m = {0, 0, 0};
  spot.direction = {0, 0, 1};
  spot.cosInner = std::cos(10 * kDeg);
  spot.cosOuter = std::cos(20 * kDeg);
  const auto at = [&](double angle) { return cpu::spotFactor(spot, 2.0 * polar(angle * kDeg, 0.7)); };
  CHECK(at(0) == 1.0);
  CHECK(at(9.9) == 1.0);
  CHECK(at(20.1) == 0.0);
  CHECK(at(60) == 0.0);
  CHECK(at(170) == 0.0);
  // Where cos φ is midway between the cosines, t = 1/2 and the smoothstep t²(3 − 2t) = 1/2.
  const double midway = std::acos((spot.cosInner + spot.cosOuter) / 2) / kDeg;
  CHECK(at(midway) == doctest::Approx(0.5).epsilon(1e-9));
  // At t = 1/4: 1/16 · 5/2 = 5/32.
  const double quarter = std::acos(spot.cosOuter + (spot.cosInner - spot.cosOuter) / 4) / kDeg;
  CHECK(at(quarter) == doctest::Approx(5.0 / 32).epsilon(1e-9));
  double previous = 1;
  for (double a = 10; a <= 20; a += 0.25) {
    CHECK(at(a) <= previous);
    previous = at(a);
  }
  PreparedLight point;
  CHECK(cpu::spotFactor(point, {1, 2, 3}) == 1.0);
}

namespace {

// A lit rectangle filling the view, with the given shader line and lights.
std::string plateScene(const std::string& shader, const std::string& lights) {
  return std::string(kCameraLine) +
         "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.2}; location = {0, 0, 0.3} };\n"
         "  shader = " + shader + "; texture = Texture.Constant { value = 0.8 } }\n" + lights;
}

RenderResult renderCpu(const TempFolder& dir, const std::string& text) {
  const std::string path = dir.write("scene.lua", text);
  RenderOptions options;
  options.samplesPerPixel = 2;
  return cpu::render(prepareScene(loadScene(path, {})), options);
}

}  // namespace

TEST_CASE("shading: an ambient light adds exactly rho times its radiance, unshadowed") {
  TempFolder dir;
  const std::string shader = "Shader.Phong { color = 0.5; specular = 0.2; shininess = 20 }";
  const std::string lamp = "lamp = Light.Point { position = {0.05, -0.05, 0.1}; intensity = 0.01 }\n";
  const RenderResult without = renderCpu(dir, plateScene(shader, lamp));
  const RenderResult with = renderCpu(dir, plateScene(shader, lamp + "sky = Light.Ambient { intensity = 0.3 }\n"));
  const double expected = 0.5 * 0.8 * 0.3;  // albedo × texture × L_a, the same at every sample
  double worst = 0;
  for (std::size_t i = 0; i < with.cameras[0].radiance.size(); ++i)
    worst = std::max(worst, std::abs(with.cameras[0].radiance[i] - without.cameras[0].radiance[i] - expected));
  CHECK(worst <= 1e-15);  // a few ulps of radiances below 1
}

TEST_CASE("shading: a point light 1e12 m away lights an untransformed plate as the closed form says") {
  // A far point light stands in for a directional one. It was refused up to here with a message
  // about a homography's singular plane on the plate's line (the radiometry audit of 2026-11-28:
  // prepare's relative test of w = 1 against the coordinates' size). Closed form per sample at
  // (x, y, 0.3) lit from (0, 0, −D): ρ·t/π · I cosθ / r², cosθ = (0.3 + D)/r.
  TempFolder dir;
  for (const double distance : {5e11, 1e12}) {
    INFO(distance);
    const double intensity = distance * distance;
    char light[128];
    std::snprintf(light, sizeof light, "sun = Light.Point { position = {0, 0, %.17g}; intensity = %.17g }\n", -distance,
                  intensity);
    const std::string path = dir.write("scene.lua", plateScene("Shader.Lambert { color = 1 }", light));
    RenderOptions options;
    options.samplesPerPixel = 1;
    const RenderResult r = cpu::render(prepareScene(loadScene(path, {})), options);
    // Every sample is within 0.15 m of the axis: r² = (0.3 + D)²(1 + ~1e-25), so the radiance is
    // 0.8/π · D²/(0.3 + D)² to double's rounding, at every pixel.
    const double expected = 0.8 / M_PI * intensity / ((0.3 + distance) * (0.3 + distance));
    double worst = 0;
    for (const double y : r.cameras[0].radiance) worst = std::max(worst, std::abs(y / expected - 1));
    CHECK(worst <= 1e-14);  // a few ulps: r², r and the products of the shading formula
  }
  // Farther is refused at the light's own line.
  TempFolder far;
  checkBodyError(far, "sun = Light.Point { position = {0, -2e12, 0}; intensity = 1 }\n", 2,
                 "Light.Point: 'position' must be within 1e12 m of the origin (a nearer light with intensity scaled by "
                 "distance² gives the same light), got 2e+12");
}

TEST_CASE("shading: several lights add linearly, for every shader") {
  TempFolder dir;
  const std::string a = "a = Light.Point { position = {0.05, -0.05, 0.1}; intensity = 0.01 }\n";
  const std::string b = "b = Light.Spot { position = {-0.05, 0.02, 0.05}; lookAt = {0, 0, 0.3}; "
                        "innerAngle = 0.05; outerAngle = 0.3; intensity = 0.02 }\n";
  const std::string c = "c = Light.Point { position = {0.0, 0.08, 0.15}; intensity = 0.005 }\n";
  for (const char* shader : {"Shader.Lambert { color = 0.6 }", "Shader.Phong { color = 0.5; specular = 0.3; shininess = 30 }",
                             "Shader.BlinnPhong { color = 0.5; specular = 0.3; shininess = 60 }",
                             "Shader.GGX { color = 0.2; roughness = 0.2; f0 = 0.9 }"}) {
    INFO(shader);
    const RenderResult ra = renderCpu(dir, plateScene(shader, a)), rb = renderCpu(dir, plateScene(shader, b));
    const RenderResult rc = renderCpu(dir, plateScene(shader, c)), all = renderCpu(dir, plateScene(shader, a + b + c));
    double worst = 0, largest = 0;
    for (std::size_t i = 0; i < all.cameras[0].radiance.size(); ++i) {
      const double sum = ra.cameras[0].radiance[i] + rb.cameras[0].radiance[i] + rc.cameras[0].radiance[i];
      worst = std::max(worst, std::abs(all.cameras[0].radiance[i] - sum));
      largest = std::max(largest, all.cameras[0].radiance[i]);
    }
    CHECK(largest > 0.01);  // the lights do light the plate
    CHECK(worst <= 1e-14 * largest);  // sums of ≤ 3 terms per sample and of 2 samples: a few ulps
  }
}

TEST_CASE("scene: shader and light constructors refuse bad values with file:line") {
  TempFolder dir;
  checkBodyError(dir, "s = Shader.Phong { shininess = 2.5 }\n", 2,
                 "Shader.Phong: 'shininess' must be an integer in [1, 10000], got 2.5");
  checkBodyError(dir, "s = Shader.BlinnPhong { shininess = 0 }\n", 2,
                 "Shader.BlinnPhong: 'shininess' must be an integer in [1, 10000], got 0");
  checkBodyError(dir, "s = Shader.Phong { specular = -1 }\n", 2, "Shader.Phong: 'specular' must be >= 0, got -1");
  checkBodyError(dir, "s = Shader.GGX { roughness = 0 }\n", 2, "Shader.GGX: 'roughness' must be in [0.01, 1], got 0");
  checkBodyError(dir, "s = Shader.GGX { f0 = {0.5, 1.5, 0.5} }\n", 2, "Shader.GGX: 'f0' must be in [0, 1], got 1.5");
  checkBodyError(dir, "\ns = Shader.GGX { rougness = 0.1 }\n", 3,
                 "Shader.GGX: unknown key 'rougness' (did you mean 'roughness'?); valid keys: color, roughness, f0");
  checkBodyError(dir, "l = Light.Ambient { position = {0, 0, 0} }\n", 2,
                 "Light.Ambient: unknown key 'position'; valid keys: intensity");
  checkBodyError(dir, "l = Light.Ambient { intensity = 0 }\n", 2, "Light.Ambient: 'intensity' must be > 0, got 0");
  checkBodyError(dir, "l = Light.Spot { position = {0, 0, 0}; outerAngle = 0.3 }\n", 2,
                 "Light.Spot: give exactly one of 'direction' = {x, y, z} and 'lookAt' = {x, y, z} (metres)");
  checkBodyError(dir, "l = Light.Spot { position = {0, 0, 0}; direction = {0, 0, 1}; lookAt = {0, 0, 1}; outerAngle = 0.3 }\n",
                 2, "Light.Spot: give exactly one of 'direction' = {x, y, z} and 'lookAt' = {x, y, z} (metres)");
  checkBodyError(dir, "l = Light.Spot { position = {0, 0, 1}; lookAt = {0, 0, 1}; outerAngle = 0.3 }\n", 2,
                 "Light.Spot: 'lookAt' must differ from 'position'");
  checkBodyError(dir, "l = Light.Spot { position = {0, 0, 0}; direction = {0, 0, 1} }\n", 2,
                 "Light.Spot: missing required 'outerAngle' (radians)");
  checkBodyError(dir, "l = Light.Spot { position = {0, 0, 0}; direction = {0, 0, 1}; innerAngle = 0.3; outerAngle = 0.2 }\n",
                 2, "Light.Spot: 'outerAngle' must be in (innerAngle, pi] (radians), got 0.2");
  // Reaching the renderer: the values as given, the spot's axis normalized.
  const std::string path = dir.write("ok.lua", std::string(kCameraLine) +
                                                   "l = Light.Spot { position = {1, 2, 3}; direction = {0, 0, -2}; outerAngle = 0.5 }\n"
                                                   "s = Object.Simple { shape = Shape.Sphere { radius = 1 }; shader = Shader.Phong { shininess = 7 } }\n");
  const Scene scene = loadScene(path, {});
  REQUIRE(scene.lights.size() == 1);
  CHECK(scene.lights[0].kind == LightKind::Spot);
  CHECK(scene.lights[0].direction == dvec3(0, 0, -1));
  CHECK(scene.lights[0].innerAngle_rad == 0.0);
  CHECK(scene.objects[0].shader.kind() == ShaderKind::Phong);
  CHECK(std::get<reflectance::Phong>(scene.objects[0].shader.model).shininess == 7);
  CHECK(std::get<reflectance::Phong>(scene.objects[0].shader.model).specular == 0.1);
}

TEST_CASE("shading: every registered reflectance model from the scene language, its defaults and its keys") {
  // host/reflectance/registry.h lists the kinds; the Lua binding iterates over it. Each kind with
  // no parameters given: its number, its default colour (1, GGX's 0: a bare metal), its name in
  // tostring; an unknown key names `color` and the kind's own keys, in the home's order.
  TempFolder dir;
  reflectance::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    const std::string name = std::string("Shader.") + Kind::kName;
    INFO(name);
    const std::string path = dir.write("ok.lua", std::string(kCameraLine) +
                                                     "assert(tostring(" + name + " {}) == '" + name + "')\n"
                                                     "s = Object.Simple { shape = Shape.Sphere { radius = 1 }; shader = " +
                                                     name + " {} }\n");
    const Scene scene = loadScene(path, {});
    REQUIRE(scene.objects.size() == 1);
    const Shader& shader = scene.objects[0].shader;
    CHECK(shader.kind() == Kind::kKind);
    CHECK(shader.color == dvec3(Kind::kDefaultColor));
    std::string keys = "color";
    for (const char* key : Kind::kKeys) keys += std::string(", ") + key;
    checkBodyError(dir, "\ns = " + name + " { colour = 1 }\n", 3,
                   name + ": unknown key 'colour' (did you mean 'color'?); valid keys: " + keys);
  });
}
