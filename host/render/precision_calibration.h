#pragma once
// `--precision auto`: which GPU precision is fastest on this device while its measured geometric
// error stays under a bound (`--max-error-px`, default 1e-6 px). A short calibration renders one
// small fixed scene (a curved NURBS plate and a sphere, 128 × 96 px, 2 spp) in every precision the
// device offers (fp32; fp64 if it has shaderFloat64; df64 if its self-test passes, and on a CPU
// device only when fp64 is not admitted: df64NotMeasured), measures speed
// and geometric error against the CPU reference (render/geometric_error.h), admits a precision
// only within its own `compare` tolerances there (calibrationExcess), and caches the result per
// device, driver and renderer build in the cache folder. The error measured there stands for
// what the precision achieves on this device; a scene's own error is what `compare`/`bench` report.
#include <optional>
#include <string>
#include <vector>

#include "model/render_options.h"
#include "model/render_result.h"

namespace dicsynth {

namespace gpu {
class Context;
class Renderer;
struct DeviceInfo;
}  // namespace gpu
struct PreparedScene;

struct PrecisionMeasurement {
  Precision precision = Precision::Fp32;
  bool available = false;
  std::string unavailable;   // why not (no shaderFloat64, df64 self-test failed, over its tolerances, not measured)
  double mraysPerSecond = 0; // camera rays of the calibration scene per second (best of 5 interleaved renders)
  double maxErrorPx = 0;     // geometric error against the CPU reference, px
};

struct PrecisionCalibration {
  std::vector<PrecisionMeasurement> modes;  // fp32, df64, fp64
  bool fromCache = false;
  std::string cachePath;  // "" without a cache folder
  double seconds = 0;     // wall time of the calibration (that of the original run when cached)
};

// Why the calibration skips df64 on this device, "" when it measures it: on a CPU device whose
// native fp64 is admitted (fp64: its measurement), df64 cannot be faster.
std::string df64NotMeasured(const gpu::DeviceInfo& device, const PrecisionMeasurement& fp64);

// Why a precision's render of the calibration scene is not admitted, "" when it is: it must stay
// within that precision's own tolerances against the CPU reference (render/compare.h, what
// `compare` applies). A device whose arithmetic or compiler breaks a precision fails here and
// --precision auto never picks it: on an NVIDIA H100 df64 built on fma products kept only float
// accuracy in the render shader though its self-test passed (bench/RESULTS.md, "GPU machines").
std::string calibrationExcess(const PreparedScene& scene, const RenderResult& reference, const RenderResult& gpu,
                              Precision precision);

// The device's calibration: read from the cache when valid for this device, driver and renderer
// build, else measured (a few seconds) and cached.
PrecisionCalibration calibratePrecisions(gpu::Context& context, gpu::Renderer& renderer);

// The cached calibration alone, never measured: none without a cache folder, or when the file is
// absent, damaged or for another device, driver or build.
std::optional<PrecisionCalibration> cachedCalibration(gpu::Context& context);

// The fastest available precision whose calibration error is ≤ maxErrorPx. Throws InputError,
// listing the measurements, when none is.
Precision choosePrecision(const PrecisionCalibration& calibration, double maxErrorPx);

// "fp32 41.2 Mrays/s 1.3e-04 px, df64 …, fp64 …" for `devices` and messages.
std::string describeCalibration(const PrecisionCalibration& calibration);

}  // namespace dicsynth
