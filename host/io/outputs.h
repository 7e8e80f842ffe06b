#pragma once
// Writers of one camera's outputs: the sensor image (TIFF, digital numbers) and the ground truth
// (OpenEXR: float radiance before the sensor + geometric layers). Each file is written to a temporary
// name in the target folder and renamed when complete, so a failure never leaves a partial file.
#include <cstdint>
#include <string>
#include <vector>

#include "model/render_result.h"
#include "model/scene.h"
#include "render/ground_truth.h"
#include "model/layers.h"
#include "sensor/sensor.h"

namespace dicsynth {

// Facts about the run recorded in each file's metadata (EXR header attributes / TIFF description).
struct OutputInfo {
  std::string sceneFile;
  int frame = 0;
  std::uint32_t seed = 0;
  int samplesPerPixel = 0;
  std::string backend, precision, device;
  std::uint32_t sceneCrc32 = 0;   // of the scene file's content: dicsynth:scene_crc32
  int downscale = 1;              // dicsynth:downscale
  std::string precisionAsked;     // --precision as given: dicsynth:precision_asked ("" : not written)
  double maxErrorPx = 0;          // with precisionAsked "auto": dicsynth:max_error_px
  std::vector<std::pair<std::string, std::string>> defines;  // -D (a sweep point's values included): dicsynth:defines
  std::vector<std::string> objectNames;  // objectNames[id - 1] is the object with objectId == id
  // Objects whose surface is a Nurbs.deform fit: name → describeDeformation(), stored in the EXR
  // header as dicsynth:deformation:<name>.
  std::vector<std::pair<std::string, std::string>> deformations;
  // OpenEXR compression of the ground truth (kExrCompressions); every one is lossless for float32
  // and uint32 channels. Only size and writing time differ (docs/outputs.md).
  std::string exrCompression = "zip";
  // What is written (--layers): the TIFF with `image`, the EXR's channels by layer (model/layers.h).
  LayerSet layers = LayerSet::all();
};

// The --exr-compression values: lossless OpenEXR compressions.
inline const std::vector<std::string> kExrCompressions = {"zip", "zips", "piz", "rle", "none"};

struct OutputFiles {
  std::string image;        // DIR/<stem>.tif; empty when info.layers has no `image`
  std::string groundTruth;  // DIR/<stem>.exr; empty when no channel of info.layers exists for this camera
};

// The EXR's channels of one camera as values, converted exactly as writeCameraOutputs converts them
// (float32, or uint32 for objectId and defects), in the file's channel list: for callers that want
// the ground truth in memory (the Python module).
struct ChannelValues {
  std::string name;                  // "Y", "disp.X", "objectId", ...
  bool isUint = false;
  std::vector<float> floats;         // isUint false
  std::vector<std::uint32_t> uints;  // isUint true
};
std::vector<ChannelValues> groundTruthChannels(const CameraImage& image, const DerivedTruth* truth,
                                               const SensorImage* sensor, const LayerSet& layers);

// `digital` holds one digital number per pixel (host/sensor), < 2^camera.bitsPerPixel.
// TIFF: 8-bit when bitsPerPixel <= 8, else 16-bit holding the raw digital number (not rescaled).
// EXR channels: Y (radiance), Z, P.X/Y/Z, N.X/Y/Z, uv.U/V (float32), objectId (uint32), mask (float32),
// plus, from `truth` when given, the layers it holds: disp.X/Y/Z, flow.X/Y, flow.mask, disparity.X/Y,
// disparity.mask, distortion.X/Y (float32; render/ground_truth.h);
// and, from `sensor` when given (host/sensor), the layers it holds: noiseFree, noise (float32, DN)
// and defects (uint32 DefectCode), with the attribute dicsynth:sensor;
// header attributes dicsynth:* (run facts, camera in OpenCV terms): the list is in outputs.cpp.
// Only the layers of info.layers are written: a layer whose data was not computed (an empty vector:
// derived layers not asked for, geometry of a render without it) is skipped.
// `dir` must exist (the caller creates it); otherwise, or if it is not writable, throws Error naming
// it. Both files are written to temporary names first and renamed only when both are complete; if
// the second rename fails the TIFF is removed again, so no image exists without its ground truth.
OutputFiles writeCameraOutputs(const std::string& dir, const std::string& stem, const Camera& camera,
                               const CameraImage& image, const std::vector<std::uint16_t>& digital,
                               const OutputInfo& info, const DerivedTruth* truth = nullptr,
                               const SensorImage* sensor = nullptr);

}  // namespace dicsynth
