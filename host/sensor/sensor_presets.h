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

struct EmvaSensor;  // model/sensor_model.h

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

// A Sensor.Emva's photons per pixel at full scale: as given, else fullWell_e / η (each as given or
// from its preset, else the first preset's), so that full scale fills the well. resolve() takes it
// from here; the scene checks its bound with it before a camera exists.
double photonsAtFullScale(const EmvaSensor& sensor);

}  // namespace dicsynth
