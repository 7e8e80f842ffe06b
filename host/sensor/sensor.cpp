// The sensor model: exposure, noise, clipping, quantization and the post-processors (sensor.h).
#include "sensor/sensor.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/exact_number.h"
#include "core/parallel.h"
#include "sensor/defects.h"
#include "sensor/noise_sampling.h"
#include "sensor/optics.h"

namespace dicsynth {
namespace {

// Round half up, exactly: floor(x + 0.5) is wrong for the largest double below 0.5 (the sum rounds
// to 1.0). The fraction x - floor(x) is exact for 0 <= x < 2^52, so comparing it with 0.5 is too.
double roundHalfUp(double x) {
  const double whole = std::floor(x);
  return x - whole >= 0.5 ? whole + 1.0 : whole;
}

std::uint16_t quantize(double value_DN, double maxDigital) {
  if (std::isnan(value_DN)) return 0;
  return static_cast<std::uint16_t>(roundHalfUp(std::clamp(value_DN, 0.0, maxDigital)));
}

// The radiance after the optical post-processors (optics.h), in their fixed order.
std::vector<double> opticalImage(const std::vector<double>& radiance, const Camera& camera) {
  const SensorModel& m = camera.sensor;
  const int w = camera.width_px, h = camera.height_px;
  const double k = double(m.downscale);
  std::vector<double> r(radiance);
  for (double& v : r)
    if (std::isnan(v)) v = 0.0;  // as digitize: NaN reads black (and must not spread in the blur)
  if (m.blur) {
    Blur b = *m.blur;
    b.sigma_px /= k;
    b.radius_px /= k;
    r = applyBlur(r, w, h, b);
  }
  if (m.vignetting || !m.dust.empty()) {
    // cos⁴ is measured from the sensor: the chief ray's angle is set by the distance from the lens centre
    // to the sensor, the pinhole distance, which for a thin lens is the image distance v = f u / (u − f)
    // (cameras/thin_lens.h). Telecentric cameras are refused at scene load (no fall-off to model).
    const double sensorDistance_m = camera.kindInfo().telecentric ? 0.0 : camera.focalScale();
    const VignettingGeometry g{w, h, camera.principalPoint_px.x, camera.principalPoint_px.y,
                               camera.pixelSize_m.x, camera.pixelSize_m.y, sensorDistance_m};
    if (m.vignetting && m.vignetting->kind == VignettingKind::Cos4)
      DS_CHECK(sensorDistance_m > 0, "camera " + camera.name + ": Vignetting.Cos4 needs a focal length");
    std::vector<DustBlob> dust = m.dust;
    for (DustBlob& d : dust) {  // scene pixels → rendered pixels, as the principal point
      d.x_px = (d.x_px + 0.5) / k - 0.5;
      d.y_px = (d.y_px + 0.5) / k - 0.5;
      d.radius_px /= k;
    }
    parallelFor(std::size_t(h), [&](std::size_t y) {
      for (int x = 0; x < w; ++x) {
        double factor = m.vignetting ? vignettingFactor(*m.vignetting, g, x, double(y)) : 1.0;
        for (const DustBlob& d : dust) factor *= dustTransmission(d, x, double(y));
        r[y * std::size_t(w) + std::size_t(x)] *= factor;
      }
    });
  }
  return r;
}

}  // namespace

std::uint16_t digitize(double radiance, const Camera& camera) {
  DS_CHECK(camera.bitsPerPixel >= 1 && camera.bitsPerPixel <= 16,
           "camera " + camera.name + ": bitsPerPixel must be in 1..16");
  const double maxDigital = double((1u << camera.bitsPerPixel) - 1u);
  double signal = camera.exposure * radiance;  // full scale = 1
  if (std::isnan(signal)) signal = 0.0;        // documented: NaN reads black
  signal = std::clamp(signal, 0.0, 1.0);
  return static_cast<std::uint16_t>(roundHalfUp(signal * maxDigital));
}

std::vector<std::uint16_t> digitize(const std::vector<double>& radiance, const Camera& camera) {
  std::vector<std::uint16_t> digital(radiance.size());
  // Blocks of 2^16 pixels on all cores: one thread took 0.016 s for 1600 × 1200, the whole sensor
  // phase of a camera without a sensor model (bench/RESULTS.md, "Truth without copies").
  parallelForBlocks(radiance.size(), std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) digital[i] = digitize(radiance[i], camera);
  });
  return digital;
}

SensorImage applySensor(const std::vector<double>& radiance, const Camera& camera, const SensorRun& run) {
  SensorImage out;
  const SensorModel& m = camera.sensor;
  if (m.empty()) {  // the plain sensor, exactly as before: nothing else is computed or stored
    out.digital = digitize(radiance, camera);
    return out;
  }
  DS_CHECK(camera.bitsPerPixel >= 1 && camera.bitsPerPixel <= 16,
           "camera " + camera.name + ": bitsPerPixel must be in 1..16");
  const int w = camera.width_px, h = camera.height_px;
  const std::size_t n = std::size_t(w) * std::size_t(h);
  DS_CHECK(radiance.size() == n, "camera " + camera.name + ": radiance has the wrong pixel count");
  const double maxDigital = double((1u << camera.bitsPerPixel) - 1u);
  out.description = describeSensor(m, camera.bitsPerPixel);

  const std::vector<double> optical = opticalImage(radiance, camera);
  if (m.defects)
    out.defects = defectMap(*m.defects, w, h, m.defects->seed.value_or(run.seed), run.cameraIndex, m.downscale);
  const double hot_DN = m.defects ? m.defects->hotSignal_DN.value_or(std::floor(maxDigital / 4)) : 0.0;
  const double stuck_DN = m.defects ? m.defects->stuck_DN.value_or(maxDigital) : 0.0;
  const bool emva = m.emva.has_value();
  const ResolvedEmva e = emva ? resolve(*m.emva, camera.bitsPerPixel) : ResolvedEmva{};
  // Beyond this mean, min(Poisson(μ), fullWell) is fullWell but with probability < e^-600 (a
  // Chernoff bound): skip the draw. Keeps huge and infinite radiances finite too.
  const double certainSaturation = emva ? e.fullWell_e + 40.0 * std::sqrt(e.fullWell_e) + 1000.0 : 0.0;

  out.digital.resize(n);
  out.noiseFree_DN.resize(n);
  if (emva) out.noise_DN.resize(n);
  parallelFor(std::size_t(h), [&](std::size_t yIndex) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = yIndex * std::size_t(w) + std::size_t(x);
      const auto code = out.defects.empty() ? DefectCode::None : DefectCode(out.defects[i]);
      const double signal = std::max(0.0, camera.exposure * optical[i]);  // full scale = 1
      double clean, value;
      if (emva) {
        // The fixed pattern (EMVA 1288's spatial nonuniformities), drawn per pixel with the frame
        // fixed: this pixel's relative photo response and its dark-signal offset (e⁻).
        double response = 1, offset_e = 0;
        if (e.prnu > 0 || e.dsnu_e > 0) {
          PixelRandom fixed(run.seed, kDefectFrame, run.cameraIndex, std::uint32_t(x), std::uint32_t(yIndex),
                            kDimSensorFixedPattern);
          const double zResponse = standardNormal(fixed), zOffset = standardNormal(fixed);
          response = std::max(0.0, 1.0 + e.prnu * zResponse);
          offset_e = e.dsnu_e * zOffset;
        }
        // Electrons: photo-electrons plus dark electrons, both Poisson; a dead pixel collects none.
        double mean_e = 0;
        if (code != DefectCode::Dead)
          mean_e = std::min(e.quantumEfficiency * e.photonsAtFullScale * signal * response + e.darkElectrons(),
                            certainSaturation);
        double electrons = mean_e;
        if (e.shotNoise && mean_e < certainSaturation) {
          PixelRandom shot(run.seed, std::uint32_t(run.frame), run.cameraIndex, std::uint32_t(x),
                           std::uint32_t(yIndex), kDimSensorShot);
          electrons = double(poisson(mean_e, shot));
        }
        electrons = std::min(electrons, e.fullWell_e);  // the well saturates
        double read = 0;
        if (e.readNoise_e > 0) {
          PixelRandom readRandom(run.seed, std::uint32_t(run.frame), run.cameraIndex, std::uint32_t(x),
                                 std::uint32_t(yIndex), kDimSensorRead);
          read = e.readNoise_e * standardNormal(readRandom);
        }
        // The dark-signal offset is read out with the charge (after the well), like the read noise;
        // being fixed, it is part of the noise-free value.
        clean = e.gain_DN_per_e * (std::min(mean_e, e.fullWell_e) + offset_e) + e.darkOffset_DN;
        value = e.gain_DN_per_e * (electrons + read + offset_e) + e.darkOffset_DN;
      } else {
        // The ideal sensor of digitize(), without its clipping (kept in the ground truth).
        clean = code == DefectCode::Dead ? 0.0 : std::min(signal, 1e12) * maxDigital;
        value = clean;
      }
      if (code == DefectCode::Hot) {
        clean += hot_DN;
        value += hot_DN;
      } else if (code == DefectCode::Stuck) {
        clean = value = stuck_DN;
      }
      out.noiseFree_DN[i] = clean;
      if (emva) out.noise_DN[i] = value - clean;
      out.digital[i] = quantize(value, maxDigital);
    }
  });
  return out;
}

std::string describeSensor(const SensorModel& m, int bitsPerPixel) {
  std::string text;
  auto add = [&](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  if (m.emva) {
    const ResolvedEmva e = resolve(*m.emva, bitsPerPixel);
    add("Sensor.Emva preset=" + (m.emva->preset.empty() ? std::string("none") : m.emva->preset) +
        " quantumEfficiency=" + exactNumber(e.quantumEfficiency) + " fullWell_e=" + exactNumber(e.fullWell_e) +
        " readNoise_e=" + exactNumber(e.readNoise_e) + " darkCurrent_e_per_s=" + exactNumber(e.darkCurrent_e_per_s) +
        " exposureTime_s=" + exactNumber(e.exposureTime_s) + " photonsAtFullScale=" + exactNumber(e.photonsAtFullScale) +
        " gain_DN_per_e=" + exactNumber(e.gain_DN_per_e) + " darkOffset_DN=" + exactNumber(e.darkOffset_DN) +
        " shotNoise=" + (e.shotNoise ? "true" : "false") +
        // Listed only when set: the header of a sensor without them stays as it was.
        (e.prnu > 0 ? " prnu=" + exactNumber(e.prnu) : std::string()) +
        (e.dsnu_e > 0 ? " dsnu_e=" + exactNumber(e.dsnu_e) : std::string()));
  } else {
    add("ideal sensor");
  }
  if (m.blur)
    add(m.blur->kind == BlurKind::Gaussian ? "Blur.Gaussian sigma_px=" + exactNumber(m.blur->sigma_px)
                                           : "Blur.Disk radius_px=" + exactNumber(m.blur->radius_px));
  if (m.vignetting) {
    if (m.vignetting->kind == VignettingKind::Cos4) {
      add("Vignetting.Cos4");
    } else {
      std::string c;
      for (double a : m.vignetting->coefficients) {
        if (!c.empty()) c += ',';
        c += exactNumber(a);
      }
      add("Vignetting.Radial coefficients=" + c);
    }
  }
  for (const DustBlob& d : m.dust)
    add("Dust center_px=" + exactNumber(d.x_px) + "," + exactNumber(d.y_px) + " radius_px=" + exactNumber(d.radius_px) +
        " opacity=" + exactNumber(d.opacity));
  if (m.defects) {
    const DefectivePixels& d = *m.defects;
    add("DefectivePixels dead=" + exactNumber(d.deadFraction) + " hot=" + exactNumber(d.hotFraction) +
        " stuck=" + exactNumber(d.stuckFraction) + " listed=" +
        std::to_string(d.dead.size() + d.hot.size() + d.stuck.size()) +
        (d.seed ? " seed=" + std::to_string(*d.seed) : std::string(" seed=render")));
  }
  if (m.downscale != 1) add("downscale=" + std::to_string(m.downscale));
  return text;
}

}  // namespace dicsynth
