// The sensor in the scene language (Sensor.Emva, Blur, Vignetting, Dust, DefectivePixels on a
// camera) and `dicsynth render` with a sensor model end to end: the EXR's noiseFree, noise and
// defects layers against the TIFF.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "exr_test_util.h"
#include "files/image_io.h"
#include "run_cli.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;
using dicsynth::test::checkBodyError;
using dicsynth::test::runCli;
using dicsynth::test::TempFolder;

namespace {

const std::string kScenes = std::string(DS_SOURCE_DIR) + "/scenes/";

}  // namespace

TEST_CASE("sensor: scene syntax reads every parameter") {
  TempFolder dir;
  const std::string path = dir.write("scene.lua", R"(
cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5};
  sensor = Sensor.Emva { preset = "scientific-cmos"; readNoise_e = 1.2; gain_DN_per_e = 0.5;
                         darkOffset_DN = 10; exposureTime_s = 0.02; shotNoise = false; prnu = 0.015; dsnu_e = 2.5 };
  postProcessing = { Vignetting.Radial { coefficients = {-0.2, 0.01} }, Blur.Disk { radius_px = 2.5 },
                     Dust { center_px = {10, 20}; radius_px = 5; opacity = 0.25 },
                     Dust { center_px = {30, 20}; radius_px = 3; opacity = 1 },
                     DefectivePixels { dead = 0.001; hot = {{1, 2}, {3, 4}}; stuck_DN = 17; seed = 99 } } }
plain = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} }
)");
  const Scene scene = loadScene(path, {});
  REQUIRE(scene.cameras.size() == 2);
  const SensorModel& m = scene.cameras[0].sensor;
  REQUIRE(m.emva);
  CHECK(m.emva->preset == "scientific-cmos");
  CHECK(*m.emva->readNoise_e == 1.2);
  CHECK(*m.emva->gain_DN_per_e == 0.5);
  CHECK(*m.emva->darkOffset_DN == 10);
  CHECK(*m.emva->exposureTime_s == 0.02);
  CHECK_FALSE(m.emva->shotNoise);
  CHECK(m.emva->prnu == 0.015);
  CHECK(m.emva->dsnu_e == 2.5);
  CHECK(resolve(*m.emva, 8).prnu == 0.015);
  CHECK(resolve(*m.emva, 8).dsnu_e == 2.5);
  CHECK_FALSE(m.emva->fullWell_e.has_value());  // from the preset, when resolved
  CHECK(resolve(*m.emva, 8).fullWell_e == 30000);
  REQUIRE(m.blur);
  CHECK(m.blur->kind == BlurKind::Disk);
  CHECK(m.blur->radius_px == 2.5);
  REQUIRE(m.vignetting);
  CHECK(m.vignetting->coefficients == std::vector<double>{-0.2, 0.01});
  REQUIRE(m.dust.size() == 2);
  CHECK(m.dust[1].x_px == 30);
  CHECK(m.dust[1].opacity == 1);
  REQUIRE(m.defects);
  CHECK(m.defects->deadFraction == 0.001);
  REQUIRE(m.defects->hot.size() == 2);
  CHECK(m.defects->hot[1].x_px == 3);
  CHECK(m.defects->hot[1].y_px == 4);
  CHECK(*m.defects->stuck_DN == 17);
  CHECK(*m.defects->seed == 99);
  CHECK(scene.cameras[1].sensor.empty());
}

TEST_CASE("sensor: scene errors name the line") {
  TempFolder dir;
  const std::string cam = "c = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-5, 1e-5};\n";
  checkBodyError(dir, "s = Sensor.Emva { readNoise = 2 }\n", 2,
                 "Sensor.Emva: unknown key 'readNoise' (did you mean 'readNoise_e'?); valid keys: preset, "
                 "quantumEfficiency, fullWell_e, readNoise_e, darkCurrent_e_per_s, exposureTime_s, "
                 "photonsAtFullScale, gain_DN_per_e, darkOffset_DN, shotNoise, prnu, dsnu_e");
  checkBodyError(dir, "s = Sensor.Emva { preset = \"webcam\" }\n", 2,
                 "Sensor.Emva: unknown 'preset' \"webcam\"; the presets are \"machine-vision-cmos\", "
                 "\"small-pixel-cmos\", \"interline-ccd\", \"scientific-cmos\"");
  checkBodyError(dir, "s = Sensor.Emva { quantumEfficiency = 1.5 }\n", 2,
                 "Sensor.Emva: 'quantumEfficiency' must be in (0, 1], got 1.5");
  checkBodyError(dir, "s = Sensor.Emva { shotNoise = 1 }\n", 2, "Sensor.Emva: 'shotNoise' must be true or false");
  checkBodyError(dir, "b = Blur.Gaussian { sigma_px = -1 }\n", 2, "Blur.Gaussian: 'sigma_px' must be in (0, 100] (px), got -1");
  checkBodyError(dir, "b = Blur.Gaussian {}\n", 2, "Blur.Gaussian: missing required 'sigma_px'");
  checkBodyError(dir, "d = Dust { center_px = {1, 2}; radius_px = 3; opacity = 2 }\n", 2,
                 "Dust: 'opacity' must be in [0, 1], got 2");
  checkBodyError(dir, "d = DefectivePixels { dead = 0.7; hot = 0.5 }\n", 2,
                 "DefectivePixels: the fractions dead + hot + stuck must not exceed 1, got 1.2");
  checkBodyError(dir, "d = DefectivePixels { dead = {{1, 2.5}} }\n", 2,
                 "DefectivePixels: 'dead' must be a fraction in [0, 1] or a list {{x, y}, ...} of pixels; entry 1 "
                 "is not {x, y} with integers in 0..65535");
  // A camera's errors name the line where its constructor call starts, and the entry's own line.
  checkBodyError(dir, "\n" + cam + "  postProcessing = { DefectivePixels { stuck = {{64, 0}} } } }\n", 3,
                 "Camera.Pinhole: DefectivePixels (line 4): pixel {64, 0} is outside the 64x48 image");
  checkBodyError(dir, cam + "  postProcessing = { Blur.Gaussian { sigma_px = 1 },\n  Blur.Disk { radius_px = 1 } } }\n", 2,
                 "Camera.Pinhole: 'postProcessing' has more than one Blur (lines 3 and 4)");
  // The sensor trial of 2026-11-29: an entry three lines below the camera was named by the camera's
  // line alone.
  checkBodyError(dir, cam + "  bitsPerPixel = 12;\n  postProcessing = {\n    DefectivePixels { stuck = {{1, 1}}; stuck_DN = 5000 } } }\n", 2,
                 "Camera.Pinhole: DefectivePixels (line 5): stuck_DN = 5000 is above the full scale 2^12 - 1 = 4095 DN "
                 "of this camera's bitsPerPixel");
  CHECK_NOTHROW(loadScene(dir.write("stuck.lua", cam + "  bitsPerPixel = 12; postProcessing = { DefectivePixels { stuck = {{1, 1}}; "
                                                       "stuck_DN = 4095 } } }\n"), {}));
  checkBodyError(dir, "d = DefectivePixels { hot = 0.1; hotSignal_DN = 1e6 }\n", 2,
                 "DefectivePixels: 'hotSignal_DN' must be in 0..65535 (DN), got 1e+06");
  // Dust that reaches no pixel centre (a position in other units, or of another image) changes nothing.
  checkBodyError(dir, cam + "  postProcessing = { Dust { center_px = {1e6, 1e6}; radius_px = 40; opacity = 0.3 } } }\n", 2,
                 "Camera.Pinhole: Dust (line 3): the blob at {1e+06, 1e+06} px of radius 40 px reaches no pixel of "
                 "the 64x48 image (pixel centres 0..63, 0..47): it would change nothing");
  checkBodyError(dir, cam + "  postProcessing = { Dust { center_px = {-10, 5}; radius_px = 10; opacity = 0.3 } } }\n", 2,
                 "Camera.Pinhole: Dust (line 3): the blob at {-10, 5} px of radius 10 px reaches no pixel of the 64x48 "
                 "image (pixel centres 0..63, 0..47): it would change nothing");
  // Partly outside: the pixels it reaches are dimmed.
  CHECK_NOTHROW(loadScene(dir.write("dust.lua", cam + "  postProcessing = { Dust { center_px = {-10, 5}; radius_px = 10.5; "
                                                      "opacity = 0.3 } } }\n"), {}));
  // Sensor.Emva's bounds (the sensor trial of 2026-11-29: a full well of 1e30 read the dark offset in
  // every pixel while noiseFree said 2079; 1e300 read noise or gain made the layers infinite).
  checkBodyError(dir, "s = Sensor.Emva { fullWell_e = 1e30 }\n", 2,
                 "Sensor.Emva: 'fullWell_e' must be in [1, 1e9] e⁻ (a well of less than one electron holds none; beyond "
                 "1e9 the shot-noise sampler loses accuracy, and real sensors hold up to ~2e6), got 1e+30");
  checkBodyError(dir, "s = Sensor.Emva { fullWell_e = 0.5 }\n", 2,
                 "Sensor.Emva: 'fullWell_e' must be in [1, 1e9] e⁻ (a well of less than one electron holds none; beyond "
                 "1e9 the shot-noise sampler loses accuracy, and real sensors hold up to ~2e6), got 0.5");
  checkBodyError(dir, "s = Sensor.Emva { readNoise_e = 1e300 }\n", 2,
                 "Sensor.Emva: 'readNoise_e' must be in [0, 1e9] e⁻ rms, got 1e+300");
  checkBodyError(dir, "s = Sensor.Emva { gain_DN_per_e = 1e300 }\n", 2,
                 "Sensor.Emva: 'gain_DN_per_e' must be in (0, 65535] DN/e⁻ (more would put one electron beyond the "
                 "whole 16-bit range), got 1e+300");
  checkBodyError(dir, "s = Sensor.Emva { photonsAtFullScale = 1e16 }\n", 2,
                 "Sensor.Emva: 'photonsAtFullScale' must be in (0, 1e15] photons, got 1e+16");
  checkBodyError(dir, "s = Sensor.Emva { fullWell_e = 1e9; quantumEfficiency = 1e-7 }\n", 2,
                 "Sensor.Emva: photonsAtFullScale = fullWell_e / quantumEfficiency = 1e+16 photons is over 1e15: give a "
                 "larger quantumEfficiency or photonsAtFullScale itself");
  CHECK_NOTHROW(loadScene(dir.write("well.lua", cam + "  sensor = Sensor.Emva { fullWell_e = 1e9; readNoise_e = 1e9; "
                                                      "gain_DN_per_e = 65535 } }\n"), {}));
  checkBodyError(dir, "s = Sensor.Emva { prnu = 0.3 }\n", 2,
                 "Sensor.Emva: 'prnu' must be in [0, 0.25] (a fraction: 0.01 is 1 % rms), got 0.3");
  checkBodyError(dir, "s = Sensor.Emva { dsnu_e = -1 }\n", 2, "Sensor.Emva: 'dsnu_e' must be in [0, 1e9] e⁻ rms, got -1");
  // A constructor without parameters says so (the message ended "valid keys: " and nothing).
  checkBodyError(dir, "v = Vignetting.Cos4 { strength = 2 }\n", 2,
                 "Vignetting.Cos4: unknown key 'strength'; Vignetting.Cos4 takes no parameters");
  checkBodyError(dir, cam + "  postProcessing = { Vignetting.Cos4 {}, 3 } }\n", 2,
                 "Camera.Pinhole: 'postProcessing' must be a list {Blur..., Vignetting..., Dust {...}, "
                 "DefectivePixels {...}}; entry 2 is a number");
  checkBodyError(dir, cam + "  sensor = Vignetting.Cos4 {} }\n", 2,
                 "Camera.Pinhole: 'sensor' must be a Sensor (Sensor.Emva { ... }), got PostProcessor");
  // A black level at full scale leaves no range (the sensor audit of 2026-11-28: every pixel read 63
  // at 6 bits, with a default gain silently made 1/fullWell); just below it is a camera.
  checkBodyError(dir, "\n" + cam + "  bitsPerPixel = 6; sensor = Sensor.Emva { darkOffset_DN = 63 } }\n", 3,
                 "Camera.Pinhole: 'sensor': darkOffset_DN = 63 leaves no range for the signal: it must be below the "
                 "full scale 2^bitsPerPixel - 1 = 63 DN");
  checkBodyError(dir, cam + "  sensor = Sensor.Emva { darkOffset_DN = 300 } }\n", 2,
                 "Camera.Pinhole: 'sensor': darkOffset_DN = 300 leaves no range for the signal: it must be below the "
                 "full scale 2^bitsPerPixel - 1 = 255 DN");
}

TEST_CASE("sensor: render writes noiseFree, noise and defects layers that add up to the TIFF") {
  TempFolder dir;
  const std::string out = dir.file("out");
  const test::CliResult r = runCli("render " + kScenes + "noisy_speckle.lua -o " + out +
                                   " --downscale 2 --spp 1 --backend cpu --seed 5");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const test::ExrContents exr = test::readExr(out + "/camera.exr");
  REQUIRE(exr.floats.count("noiseFree") == 1);
  REQUIRE(exr.floats.count("noise") == 1);
  REQUIRE(exr.floats.count("defects") == 1);
  const std::string description = exr.spec.get_string_attribute("dicsynth:sensor");
  CAPTURE(description);
  CHECK(description.rfind("Sensor.Emva preset=machine-vision-cmos", 0) == 0);
  const GrayImage tiff = readGrayImage(out + "/camera.tif");  // 12 bits in a 16-bit TIFF: value/65535
  REQUIRE(tiff.width == 160);
  REQUIRE(tiff.height == 120);
  const auto& clean = exr.floats.at("noiseFree");
  const auto& noise = exr.floats.at("noise");
  // OIIO reads a uint channel as float normalized to [0, 1]: the codes are value × (2^32 - 1).
  std::vector<double> defects;
  for (float v : exr.floats.at("defects")) defects.push_back(std::round(double(v) * 4294967295.0));
  double noiseSquares = 0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const double dn = std::round(tiff.pixels[i] * 65535);
    // The README's relation: DN = clamp(round(noiseFree + noise), 0, 4095). The layers are float32
    // (relative rounding 6e-8, i.e. < 3e-4 DN below 4096 each), so a sum within 1e-3 DN of a
    // rounding edge may round the other way: then DN is one of its two neighbours.
    const double sum = double(clean[i]) + double(noise[i]);
    const double expected = std::clamp(std::floor(sum + 0.5), 0.0, 4095.0);
    const double edge = std::fabs(sum + 0.5 - std::round(sum + 0.5));
    if (edge > 1e-3) REQUIRE(dn == expected);
    else REQUIRE(std::fabs(dn - expected) <= 1);
    noiseSquares += double(noise[i]) * double(noise[i]);
  }
  // There is noise: its rms is at least the read noise, 2.4 e⁻ × K (4032/10500 DN/e⁻) = 0.92 DN.
  CHECK(std::sqrt(noiseSquares / double(clean.size())) > 0.9);
  // The listed pixels at the rendered size (--downscale 2): dead (50, 50), stuck (100, 75).
  CHECK(defects[50 * 160 + 50] == 1);
  CHECK(defects[75 * 160 + 100] == 3);
  CHECK(std::count(defects.begin(), defects.end(), 2.0) < 20);  // hot: 2e-4 of 19200 pixels, ~4
  CHECK(std::round(tiff.pixels[75 * 160 + 100] * 65535) == 4095);
  CHECK(clean[50 * 160 + 50] == 63.0f);  // a dead pixel reads the dark offset, floor(4095/64)
  // Another --seed: other noise (and other pixel samples, so another radiance), the same defects
  // (the scene's DefectivePixels has its own seed).
  REQUIRE(runCli("render " + kScenes + "noisy_speckle.lua -o " + dir.file("b") + " --downscale 2 --spp 1 --backend cpu --seed 6")
              .exitCode == 0);
  const test::ExrContents other = test::readExr(dir.file("b/camera.exr"));
  CHECK(other.floats.at("defects") == exr.floats.at("defects"));
  CHECK(other.floats.at("noise") != noise);
}

TEST_CASE("sensor: a scene without a sensor model writes no sensor layers") {
  TempFolder dir;
  const test::CliResult r = runCli("render " + kScenes + "rectangle.lua -o " + dir.file("out") +
                                   " --downscale 8 --spp 1 --backend cpu");
  REQUIRE(r.exitCode == 0);
  const test::ExrContents exr = test::readExr(dir.file("out/camera.exr"));
  CHECK(exr.floats.count("noiseFree") == 0);
  CHECK(exr.floats.count("noise") == 0);
  CHECK(exr.floats.count("defects") == 0);
  CHECK(exr.spec.get_string_attribute("dicsynth:sensor").empty());
}
