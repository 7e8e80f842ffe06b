// The presets of Sensor.Emva and the resolution of a Sensor.Emva's values (sensor_model.h).
#include "sensor/sensor_presets.h"

#include <cmath>

#include "core/error.h"
#include "model/sensor_model.h"

namespace dicsynth {

const std::vector<SensorPreset>& sensorPresets() {
  // Typical values of each class (see the header): what DIC cameras of that class show on their
  // EMVA 1288 sheets, rounded. Dark current at room temperature, uncooled unless said otherwise.
  static const std::vector<SensorPreset> presets = {
      {"machine-vision-cmos",
       "global-shutter CMOS machine-vision sensor with 3.45 um pixels (class of the 2nd-generation "
       "Sony Pregius sensors common in DIC cameras)",
       0.65, 10500, 2.4, 3.0, 0.01},
      {"small-pixel-cmos",
       "rolling-shutter back-illuminated CMOS with 2.4 um pixels (high-resolution industrial "
       "cameras)",
       0.75, 6000, 2.0, 1.0, 0.01},
      {"interline-ccd",
       "interline-transfer CCD with 6.45 um pixels (class of the 1.4-megapixel CCDs of older DIC "
       "systems)",
       0.55, 18000, 8.0, 1.0, 0.01},
      {"scientific-cmos",
       "front-illuminated scientific CMOS with 6.5 um pixels, cooled (class of the 5.5-megapixel "
       "sCMOS cameras)",
       0.60, 30000, 1.6, 0.1, 0.01},
  };
  return presets;
}

const SensorPreset* findSensorPreset(const std::string& name) {
  for (const SensorPreset& p : sensorPresets())
    if (name == p.name) return &p;
  return nullptr;
}

std::string sensorPresetNames() {
  std::string names;
  for (const SensorPreset& p : sensorPresets()) names += (names.empty() ? "\"" : ", \"") + std::string(p.name) + "\"";
  return names;
}

namespace {

// The preset whose values fill what a Sensor.Emva leaves unset. Without a preset: the
// machine-vision class's values, so that Sensor.Emva {} is realistic.
const SensorPreset& basePreset(const EmvaSensor& s) {
  if (s.preset.empty()) return sensorPresets().front();
  const SensorPreset* preset = findSensorPreset(s.preset);
  DS_CHECK(preset != nullptr, "unknown sensor preset '" + s.preset + "'");
  return *preset;
}

}  // namespace

double photonsAtFullScale(const EmvaSensor& s) {
  const SensorPreset& base = basePreset(s);
  // Full scale of the ideal sensor (exposure·radiance = 1) fills the well: the same radiance
  // reaches the top of the range with or without a sensor model.
  return s.photonsAtFullScale.value_or(s.fullWell_e.value_or(base.fullWell_e) /
                                       s.quantumEfficiency.value_or(base.quantumEfficiency));
}

ResolvedEmva resolve(const EmvaSensor& s, int bitsPerPixel) {
  DS_CHECK(bitsPerPixel >= 1 && bitsPerPixel <= 16, "bitsPerPixel must be in 1..16");
  const SensorPreset& base = basePreset(s);
  const double maxDigital = double((1u << bitsPerPixel) - 1u);
  ResolvedEmva r{};
  r.quantumEfficiency = s.quantumEfficiency.value_or(base.quantumEfficiency);
  r.fullWell_e = s.fullWell_e.value_or(base.fullWell_e);
  r.readNoise_e = s.readNoise_e.value_or(base.readNoise_e);
  r.darkCurrent_e_per_s = s.darkCurrent_e_per_s.value_or(base.darkCurrent_e_per_s);
  r.exposureTime_s = s.exposureTime_s.value_or(base.exposureTime_s);
  r.photonsAtFullScale = photonsAtFullScale(s);
  // A black level of 1/64 of the range keeps the read noise of dark pixels from being clipped.
  r.darkOffset_DN = s.darkOffset_DN.value_or(std::floor(maxDigital / 64.0));
  // The gain maps a full well onto the rest of the range: the well and the ADC saturate together.
  // The camera refuses an offset at or above full scale (scene/sensor_constructors.cpp), so it is > 0.
  DS_CHECK(r.darkOffset_DN < maxDigital, "darkOffset_DN below full scale");
  r.gain_DN_per_e = s.gain_DN_per_e.value_or((maxDigital - r.darkOffset_DN) / r.fullWell_e);
  r.shotNoise = s.shotNoise;
  r.prnu = s.prnu;  // the presets' classes are quoted without their nonuniformities: 0 unless given
  r.dsnu_e = s.dsnu_e;
  return r;
}

}  // namespace dicsynth
