#pragma once
// What a scene says about a camera's sensor and the post-processors around it (Camera::sensor),
// as read by host/scene/sensor_constructors.cpp and applied by host/sensor/sensor.h after either
// backend. A camera whose SensorModel is empty() is digitized exactly as before (sensor.h's
// digitize): no noise, no post-processing, no extra output layer, no cost.
//
// Units are in the names: _e electrons, _DN digital numbers, _px pixels of the image as the scene
// declares it (before --downscale), _s seconds. Pipeline order and formulas: docs/sensor.md.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dicsynth {

// Sensor.Emva: the linear camera model of EMVA 1288 (release 4.0, section 2), per pixel:
//   photons μ_p = photonsAtFullScale · max(0, exposure · radiance)
//   electrons μ_e = η μ_p + darkCurrent_e_per_s · exposureTime_s; n ~ Poisson(μ_e)
//   y = K (min(n, fullWell_e) + σ_d z) + darkOffset_DN, z ~ N(0, 1);  DN = clamp(round(y), 0, 2^b-1)
// and, when asked for, the spatial nonuniformities of the same standard (a fixed pattern: the same in
// every frame), per pixel with z_p, z_o ~ N(0, 1) drawn once: photo-electrons η μ_p max(0, 1 + prnu z_p)
// (PRNU), and the dark signal plus dsnu_e z_o electrons added with the read noise (DSNU).
// Parameters left unset take their value from the preset, else the defaults in resolve() below.
struct EmvaSensor {
  std::string preset;                         // name in sensor_presets.h, "" for none
  std::optional<double> quantumEfficiency;    // η, electrons per photon, (0, 1]
  std::optional<double> fullWell_e;           // saturation capacity, > 0
  std::optional<double> readNoise_e;          // σ_d, temporal dark noise (rms), >= 0
  std::optional<double> darkCurrent_e_per_s;  // μ_I, >= 0
  std::optional<double> exposureTime_s;       // integration time of the dark current, >= 0
  std::optional<double> photonsAtFullScale;   // photons per pixel at exposure·radiance = 1
  std::optional<double> gain_DN_per_e;        // K, overall system gain, > 0
  std::optional<double> darkOffset_DN;        // black level added before quantization, >= 0
  bool shotNoise = true;                      // false: n = μ_e (to study read noise alone)
  double prnu = 0;                            // photo-response nonuniformity: rms relative gain, [0, 0.25]
  double dsnu_e = 0;                          // dark-signal nonuniformity: rms offset (e⁻), >= 0
};

// EmvaSensor with every value known, for a given bitsPerPixel (defaults depend on it).
struct ResolvedEmva {
  double quantumEfficiency, fullWell_e, readNoise_e, darkCurrent_e_per_s, exposureTime_s;
  double photonsAtFullScale, gain_DN_per_e, darkOffset_DN;
  bool shotNoise;
  double prnu, dsnu_e;
  // Mean dark electrons per exposure: darkCurrent_e_per_s · exposureTime_s.
  double darkElectrons() const { return darkCurrent_e_per_s * exposureTime_s; }
};

enum class BlurKind : std::uint8_t { Gaussian, Disk };
struct Blur {  // Blur.Gaussian / Blur.Disk: the lens's point-spread function, in image pixels
  BlurKind kind = BlurKind::Gaussian;
  double sigma_px = 0;   // Gaussian standard deviation
  double radius_px = 0;  // Disk (defocus) radius
};

enum class VignettingKind : std::uint8_t { Cos4, Radial };
struct Vignetting {  // Vignetting.Cos4 / Vignetting.Radial: a factor on the radiance
  VignettingKind kind = VignettingKind::Cos4;
  std::vector<double> coefficients;  // Radial: a1, a2, a3 of 1 + a1 ρ² + a2 ρ⁴ + a3 ρ⁶
};

struct DustBlob {  // Dust: transmission 1 - opacity · (1 + cos(π d / radius)) / 2 for d < radius
  double x_px = 0, y_px = 0;  // centre, OpenCV pixel frame
  double radius_px = 0;
  double opacity = 0;  // [0, 1]: the fraction of light the blob's centre removes
};

// Codes of the defect map (EXR layer `defects`).
enum class DefectCode : std::uint8_t { None = 0, Dead = 1, Hot = 2, Stuck = 3 };

struct PixelPosition {
  int x_px = 0, y_px = 0;
};

struct DefectivePixels {  // DefectivePixels { ... }
  double deadFraction = 0, hotFraction = 0, stuckFraction = 0;  // drawn per pixel from the seed
  std::optional<std::uint32_t> seed;                            // default: render --seed
  std::vector<PixelPosition> dead, hot, stuck;                  // explicit pixels (win over drawn)
  std::optional<double> hotSignal_DN;  // added to a hot pixel; default 1/4 of 2^b - 1
  std::optional<double> stuck_DN;      // a stuck pixel's value; default 2^b - 1
};

struct SensorModel {
  std::optional<EmvaSensor> emva;  // nullopt: the ideal sensor DN = exposure·radiance·(2^b - 1)
  std::optional<Blur> blur;
  std::optional<Vignetting> vignetting;
  std::vector<DustBlob> dust;
  std::optional<DefectivePixels> defects;
  // Set by --downscale (geometry/prepare.cpp): pixel lengths and positions above are in the
  // scene's pixels; the rendered image has `downscale` times fewer in x and y.
  int downscale = 1;

  bool empty() const { return !emva && !blur && !vignetting && dust.empty() && !defects; }
};

// The values of `sensor` for a bitsPerPixel: the preset's values where the scene gave none, else
// the documented defaults. Throws Error for an unknown preset (the scene reader checks it first).
ResolvedEmva resolve(const EmvaSensor& sensor, int bitsPerPixel);

}  // namespace dicsynth
