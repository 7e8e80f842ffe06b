#pragma once
// The sensor: radiance before the sensor → digital numbers. Applied after either backend.
//
// A camera without a sensor model (Camera::sensor empty) goes through digitize() alone, as it did
// before sensor models existed. With one, applySensor() runs the pipeline of docs/sensor.md:
//   radiance → blur → vignetting → dust → exposure → electrons (Sensor.Emva: shot noise, full well,
//   read noise, gain, dark offset; else the ideal sensor) → defective pixels → quantization.
#include <cstdint>
#include <string>
#include <vector>

#include "model/scene.h"

namespace dicsynth {

// digital number = round(clamp(exposure * radiance, 0, 1) * (2^bitsPerPixel - 1)), rounding halves
// up. Radiance 1/exposure is full scale; brighter pixels saturate (clip) at 2^bits - 1.
// Rounding is exact (no floor(x + 0.5) double-rounding: 0.49999999999999994 rounds to 0).
// NaN radiance (a sample that failed numerically) reads 0, like an unlit pixel, rather than an
// undefined float → integer cast; +inf saturates. Throws Error if bitsPerPixel is outside 1..16.
std::uint16_t digitize(double radiance, const Camera& camera);
std::vector<std::uint16_t> digitize(const std::vector<double>& radiance, const Camera& camera);

// Which image of the run this is: the noise of pixel (x, y) is a function of (seed, frame,
// cameraIndex, x, y) alone (noise_sampling.h); the defect map of (DefectivePixels.seed or seed,
// cameraIndex, x, y).
struct SensorRun {
  std::uint32_t seed = 0;         // render --seed
  int frame = 0;
  std::uint32_t cameraIndex = 0;  // index in the scene's (sorted) camera list
};

struct SensorImage {
  std::vector<std::uint16_t> digital;  // what the TIFF holds
  // Ground truth, empty when the camera has no sensor model (then digital == digitize(...)):
  std::vector<double> noiseFree_DN;    // the image without temporal noise, before rounding and
                                       // clipping (may exceed 2^b - 1 or, never, fall below 0)
  std::vector<double> noise_DN;        // only with Sensor.Emva: the noise added, so that
                                       // digital = clamp(round(noiseFree_DN + noise_DN), 0, 2^b - 1)
  std::vector<std::uint8_t> defects;   // only with DefectivePixels: DefectCode per pixel
  std::string description;             // the model and its resolved values (EXR dicsynth:sensor)
};

// Runs the camera's sensor model on `radiance` (width × height of the camera, row-major).
SensorImage applySensor(const std::vector<double>& radiance, const Camera& camera, const SensorRun& run);

// The model's resolved parameters as one line, e.g. "Sensor.Emva preset=... eta=0.65 ...; Blur...".
std::string describeSensor(const SensorModel& model, int bitsPerPixel);

}  // namespace dicsynth
