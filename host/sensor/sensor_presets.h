#pragma once
// Named parameter sets for Sensor.Emva { preset = "..." }, each shaped like the table of an EMVA 1288
// data sheet (quantum efficiency, saturation capacity, temporal dark noise, dark current).
//
// These are TYPICAL values of a sensor class, rounded, as they appear across published camera data
// sheets of that class; they are not copied from one vendor's sheet and describe no particular
// camera. Take your own camera's EMVA 1288 sheet when the numbers matter, and override any field.
#include <string>
#include <vector>

namespace dicsynth {

struct SensorPreset {
  const char* name;
  const char* description;   // sensor class and the basis of the numbers
  double quantumEfficiency;  // η at the peak of the class's green response (~525 nm)
  double fullWell_e;         // saturation capacity
  double readNoise_e;        // temporal dark noise σ_d
  double darkCurrent_e_per_s;
  double exposureTime_s;     // a typical exposure for DIC with that class
};

// All presets, in documentation order.
const std::vector<SensorPreset>& sensorPresets();
// The preset called `name`, or nullptr.
const SensorPreset* findSensorPreset(const std::string& name);
// "a", "b", ... for messages.
std::string sensorPresetNames();

}  // namespace dicsynth
