// One camera's output pair: the sensor image (TIFF) and its ground truth (OpenEXR).
//
// Ground-truth EXR, one part, scanline, zip-compressed (lossless). Its channels, per layer, with
// their names and types: the layer schema (model/layers.cpp); their meanings, units and which
// pixels they refer to: docs/outputs.md. Background pixels hold NaN in Z, P, N and uv (and in disp,
// flow, disparity where undefined). OpenEXR stores channels sorted by name, so a reader sees them
// in the file's order (OIIO: Y, Z, mask, objectId, N.*, P.*, uv.*): find them by name.
//
// Header attributes, all strings; numbers are written with 17 significant digits, so every double
// parses back exactly; lists are separated by single spaces:
//   dicsynth:version, :scene, :frame, :seed, :spp, :backend, :precision, :device, :camera,
//   dicsynth:scene_crc32, :defines, :downscale, :precision_asked[, :max_error_px], :build
//                                     what else makes the file (provenance(), also in the TIFF)
//   dicsynth:objects                  comma-separated object names, objectId order
//   dicsynth:camera_matrix            fx 0 cx 0 fy cy 0 0 1 (row-major, pixels, OpenCV)
//   dicsynth:distortion_coefficients  k1 k2 p1 p2 k3 (OpenCV order)
//   dicsynth:R, dicsynth:t            x_cam = R·x_world + t (R row-major, t in metres)
//   dicsynth:image_size               w h
//   dicsynth:bits_per_pixel, :exposure, :fill_factor
//   dicsynth:reference_frame          in every file render writes
//   dicsynth:disparity_camera         rig cameras, with disparity
//   dicsynth:sensor                   the sensor model's resolved parameters, with its layers
//   dicsynth:deformation:<object>     a Nurbs.deform surface: its field and fit (describeDeformation)
// Plus OpenEXR's standard worldToCamera (float 4x4, Imath row-vector convention, camera frame
// x right, y UP, z forward as the OpenEXR standard defines it, i.e. OpenCV's frame with y negated)
// and PixelAspectRatio = pixelSize.x / pixelSize.y. No DateTime: the same render gives the same file.
#include "io/outputs.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <future>
#include <iterator>
#include <optional>
#include <system_error>

#include "core/atomic_file.h"
#include "core/env_count.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/json.h"
#include "core/module_folder.h"
#include "core/parallel.h"
#include "core/termination.h"
#include "core/version.h"
#include "files/image_io.h"
#include "io/opencv_camera.h"

namespace dicsynth {
namespace {

template <typename Container>
std::string formatNumbers(const Container& values) {
  std::string text;
  for (double v : values) {
    if (!text.empty()) text += ' ';
    text += exactNumberPlainZero(v);
  }
  return text;
}

// What makes a file beyond the camera, in both files' metadata: with the scene's own content
// (its CRC-32, the scene being `dicsynth:scene`), the defines, the options that change values and
// the code's build, a file says how to make it again (the reproducibility trial of 2026-11-29 found
// the defines, the scene's content, the downscale, the precision asked and the build in no header,
// and the TIFF without spp, backend, precision or device).
std::vector<std::pair<std::string, std::string>> provenance(const OutputInfo& info) {
  char crc[16];
  std::snprintf(crc, sizeof crc, "%08x", unsigned(info.sceneCrc32));
  Json::Value defines(Json::objectValue);
  for (const auto& [name, value] : info.defines) defines[name] = value;  // as given: the -D text
  std::string definesText = json::write(defines, false);
  if (!definesText.empty() && definesText.back() == '\n') definesText.pop_back();
  std::vector<std::pair<std::string, std::string>> out = {
      {"scene_crc32", crc},
      {"defines", definesText},
      {"downscale", std::to_string(info.downscale)},
      {"precision_asked", info.precisionAsked}};
  if (info.precisionAsked == "auto") out.emplace_back("max_error_px", exactNumber(info.maxErrorPx));
  out.emplace_back("build", codeBuildIdText());
  return out;
}

std::string tiffDescription(const Camera& camera, const OutputInfo& info) {
  const int bits = camera.bitsPerPixel;
  const std::string container = bits <= 8 ? "an 8-bit container" : "a 16-bit container";
  std::string text = "dicsynth: raw " + std::to_string(bits) + "-bit digital numbers in " + container +
                     "; camera " + camera.name + "; frame " + std::to_string(info.frame) + "; scene " +
                     info.sceneFile + "; seed " + std::to_string(info.seed) + "; spp " +
                     std::to_string(info.samplesPerPixel) + "; backend " + info.backend + "; precision " +
                     info.precision + "; device " + info.device;
  for (const auto& [name, value] : provenance(info)) text += "; " + name + " " + value;
  return text + "; dicsynth " + kVersion;
}

// One EXR channel: its name, its type and how to fill it. fill(first, count, out, stride) writes the
// 32-bit words of pixels first .. first + count − 1 to out[0], out[stride], ...: one inlined loop per
// channel and band of rows (a std::function call per pixel and channel showed in perf: bench/
// RESULTS.md, "Sweeps").
struct ExrChannel {
  std::string name;
  bool uintValue = false;  // objectId, defects: exact 32-bit integers; the others float32
  std::function<void(std::size_t, std::size_t, std::uint32_t*, std::size_t)> fill;
};

// A float32 channel whose value at pixel i is get(i).
template <class Get>
ExrChannel floatChannel(std::string name, Get get) {
  return {std::move(name), false, [get](std::size_t first, std::size_t count, std::uint32_t* out, std::size_t stride) {
            for (std::size_t k = 0; k < count; ++k) {
              const float v = get(first + k);
              std::memcpy(out + k * stride, &v, sizeof v);
            }
          }};
}

// A uint32 channel whose value at pixel i is get(i).
template <class Get>
ExrChannel uintChannel(std::string name, Get get) {
  return {std::move(name), true, [get](std::size_t first, std::size_t count, std::uint32_t* out, std::size_t stride) {
            for (std::size_t k = 0; k < count; ++k) out[k * stride] = get(first + k);
          }};
}

// The channels of the file: the backend's layers, then the derived ones that `truth` holds, then the
// sensor's; names and types from the layer schema (model/layers.h), in its order per layer.
std::vector<ExrChannel> exrChannels(const CameraImage& image, const DerivedTruth* truth,
                                    const SensorImage* sensor, const LayerSet& layers) {
  std::vector<ExrChannel> ch;
  // Channel k of `layer`, named and typed (float32 or uint32) as the schema says; get(i) is pixel
  // i's value.
  auto add = [&ch](Layer layer, int k, auto get) {
    const LayerChannel& c = layerSpec(layer).channels[std::size_t(k)];
    if (c.uint32)
      ch.push_back(uintChannel(c.name, [get](std::size_t i) { return std::uint32_t(get(i)); }));
    else
      ch.push_back(floatChannel(c.name, [get](std::size_t i) { return float(get(i)); }));
  };
  auto addValues = [&](Layer layer, int k, const auto& v) {
    if (!v.empty()) add(layer, k, [&v](std::size_t i) { return v[i]; });
  };
  auto addVec2 = [&](Layer layer, const std::vector<dvec2>& v) {
    if (v.empty()) return;
    add(layer, 0, [&v](std::size_t i) { return v[i].x; });
    add(layer, 1, [&v](std::size_t i) { return v[i].y; });
  };
  auto addVec3 = [&](Layer layer, const std::vector<dvec3>& v) {
    if (v.empty()) return;
    add(layer, 0, [&v](std::size_t i) { return v[i].x; });
    add(layer, 1, [&v](std::size_t i) { return v[i].y; });
    add(layer, 2, [&v](std::size_t i) { return v[i].z; });
  };
  if (layers.has(Layer::Radiance)) addValues(Layer::Radiance, 0, image.radiance);
  if (layers.has(Layer::Depth)) addValues(Layer::Depth, 0, image.depth_m);
  if (layers.has(Layer::P)) addVec3(Layer::P, image.position_m);
  if (layers.has(Layer::Normal)) addVec3(Layer::Normal, image.normal);
  if (layers.has(Layer::Uv)) addVec2(Layer::Uv, image.uv);
  if (layers.has(Layer::Mask)) {
    addValues(Layer::Mask, 0, image.objectId);
    add(Layer::Mask, 1, [&](std::size_t i) { return image.objectId[i] > 0 ? 1.0f : 0.0f; });
  }
  if (truth) {
    if (layers.has(Layer::Disp)) addVec3(Layer::Disp, truth->displacement_m);
    if (layers.has(Layer::Flow)) {
      addVec2(Layer::Flow, truth->flow_px);
      addValues(Layer::Flow, 2, truth->flowMask);
    }
    if (layers.has(Layer::Disparity)) {
      addVec2(Layer::Disparity, truth->disparity_px);
      addValues(Layer::Disparity, 2, truth->disparityMask);
    }
    if (layers.has(Layer::Distortion)) addVec2(Layer::Distortion, truth->distortion());
    if (layers.has(Layer::FieldError)) addVec3(Layer::FieldError, truth->fieldError_m);
  }
  if (sensor) {
    if (layers.has(Layer::Noise)) {
      addValues(Layer::Noise, 0, sensor->noiseFree_DN);
      addValues(Layer::Noise, 1, sensor->noise_DN);
    }
    if (layers.has(Layer::Defects)) addValues(Layer::Defects, 0, sensor->defects);
  }
  return ch;
}

void addMetadata(Imf::Header& header, const Camera& camera, const OutputInfo& info) {
  auto attribute = [&header](const char* name, const std::string& value) {
    header.insert(name, Imf::StringAttribute(value));
  };
  const OpenCvCamera cv = toOpenCv(camera);
  std::string objects;
  for (const std::string& name : info.objectNames) objects += (objects.empty() ? "" : ",") + name;

  attribute("dicsynth:version", kVersion);
  attribute("dicsynth:scene", info.sceneFile);
  attribute("dicsynth:frame", std::to_string(info.frame));
  attribute("dicsynth:seed", std::to_string(info.seed));
  attribute("dicsynth:spp", std::to_string(info.samplesPerPixel));
  attribute("dicsynth:backend", info.backend);
  attribute("dicsynth:precision", info.precision);
  attribute("dicsynth:device", info.device);
  for (const auto& [name, value] : provenance(info)) attribute(("dicsynth:" + name).c_str(), value);
  attribute("dicsynth:camera", camera.name);
  attribute("dicsynth:objects", objects);
  for (const auto& [object, text] : info.deformations) attribute(("dicsynth:deformation:" + object).c_str(), text);
  attribute("dicsynth:camera_matrix", formatNumbers(cv.cameraMatrix));
  attribute("dicsynth:distortion_coefficients", formatNumbers(cv.distortion));
  // The camera kind and what OpenCV's matrix cannot say (docs/outputs.md; cameras/<kind>.h: header()).
  std::visit(
      [&](const auto& kind) {
        attribute("dicsynth:camera_model", kind.kModelName);
        for (const auto& [name, value] : kind.header()) attribute((std::string("dicsynth:") + name).c_str(), exactNumber(value));
      },
      camera.model);
  attribute("dicsynth:R", formatNumbers(cv.R));
  attribute("dicsynth:t", formatNumbers(cv.t));
  attribute("dicsynth:image_size",
                 std::to_string(camera.width_px) + " " + std::to_string(camera.height_px));
  attribute("dicsynth:bits_per_pixel", std::to_string(camera.bitsPerPixel));
  attribute("dicsynth:exposure", exactNumber(camera.exposure));
  attribute("dicsynth:fill_factor", exactNumber(camera.fillFactor));
  attribute("Software", std::string("dicsynth ") + kVersion);
  // No capDate (OpenEXR's date): the same render gives the same file.

  // OpenEXR's worldToCamera: camera frame with y up. A column-major GLM matrix for column vectors
  // has the same memory layout as Imath's row-major matrix for row vectors, so copy in GLM order.
  dmat4 exrCameraFromWorld = cameraFromWorld(camera);
  for (int col = 0; col < 4; ++col) exrCameraFromWorld[col][1] = -exrCameraFromWorld[col][1];
  float worldToCamera[16];
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) worldToCamera[4 * col + row] = float(exrCameraFromWorld[col][row]);
  Imath::M44f m;
  std::memcpy(&m[0][0], worldToCamera, sizeof worldToCamera);
  Imf::addWorldToCamera(header, m);
  header.pixelAspectRatio() = float(camera.pixelSize_m.x / camera.pixelSize_m.y);
}

// OpenEXR's compression of each name of kExrCompressions, in its order.
Imf::Compression exrCompression(const std::string& name) {
  static const Imf::Compression kinds[] = {Imf::ZIP_COMPRESSION, Imf::ZIPS_COMPRESSION, Imf::PIZ_COMPRESSION,
                                           Imf::RLE_COMPRESSION, Imf::NO_COMPRESSION};
  DS_CHECK(kExrCompressions.size() == std::size(kinds), "one OpenEXR compression per kExrCompressions name");
  std::string names;
  for (std::size_t k = 0; k < kExrCompressions.size(); ++k) {
    if (name == kExrCompressions[k]) return kinds[k];
    names += (k == 0 ? "" : k + 1 == kExrCompressions.size() ? " or " : ", ") + kExrCompressions[k];
  }
  throw InputError("EXR compression '" + name + "': expected " + names);
}

// Rows per writePixels call: 64, or $DICSYNTH_EXR_BAND_ROWS (a measurement knob). A call compresses
// its blocks (16 rows each in zip) on the pool and returns when all are done, so 64 rows keep at most
// 4 threads busy: right on 2 cores (measured fastest there, bench/RESULTS.md), a cap on more. On an
// NVIDIA H200 machine's 16 cores Figure 1's write phase took 0.46 s, as on 2 cores; the knob lets
// the next GPU machine measure wider bands (scripts/gpu-checks.sh, phases) before the default changes.
// The file's bytes do not depend on it (the blocks are the compression's).
int exrBandRows() {
  static const int rows = int(envCount("DICSYNTH_EXR_BAND_ROWS", 64, 1, 65536));
  return rows;
}

// OpenEXR compresses the blocks of one writePixels call on its global thread pool (16 rows per
// zip block, 32 per piz). Sized once per process to the machine's cores; the calling thread does
// the file I/O.
void useAllCoresForExr() {
  static const bool once = [] {
    Imf::setGlobalThreadCount(int(hardwareThreads()));
    return true;
  }();
  (void)once;
}

// OpenEXR's output stream on the temporary file's descriptor (AtomicFile::duplicateFd, closed here):
// the file is never reopened by name (core/termination.h). Positioned writes (pwrite): the
// descriptor's own offset is not used.
class DescriptorOStream : public Imf::OStream {
 public:
  DescriptorOStream(int fd, const std::string& name) : Imf::OStream(name.c_str()), fd_(fd) {}
  ~DescriptorOStream() override { ::close(fd_); }
  void write(const char c[], int n) override {
    for (int done = 0; done < n;) {
      const ssize_t w = ::pwrite(fd_, c + done, std::size_t(n - done), off_t(position_));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) throw Error(std::string("write failed: ") + std::strerror(w < 0 ? errno : ENOSPC));
      done += int(w);
      position_ += std::uint64_t(w);
    }
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = position; }

 private:
  int fd_;
  std::uint64_t position_ = 0;
};

void writeGroundTruthExr(AtomicFile& file, const Camera& camera, const CameraImage& image,
                         const DerivedTruth* truth, const SensorImage* sensor, const OutputInfo& info,
                         const std::vector<ExrChannel>& channels) {
  const std::string& path = file.finalPath();
  const int channelCount = int(channels.size());
  const int width = image.width_px;
  Imf::Header header(width, image.height_px);
  header.compression() = exrCompression(info.exrCompression);
  // Deflate level 1 for zip and zips: on Figure 1 the write is faster than at OpenEXR's default
  // level 4 for a slightly larger file (bench/RESULTS.md, "Speed as a user times it"). OpenEXR
  // hands each block to compress2, which in dicsynth's binaries is libdeflate's (io/zip_deflate.cpp).
  header.zipCompressionLevel() = 1;
  for (const ExrChannel& c : channels)  // objectId, defects: exact 32-bit integers; the others float32
    header.channels().insert(c.name, Imf::Channel(c.uintValue ? Imf::UINT : Imf::FLOAT));
  addMetadata(header, camera, info);
  if (truth) {
    header.insert("dicsynth:reference_frame", Imf::StringAttribute(std::to_string(truth->referenceFrame)));
    if (!truth->disparityCamera.empty())
      header.insert("dicsynth:disparity_camera", Imf::StringAttribute(truth->disparityCamera));
  }
  if (sensor && !sensor->description.empty()) header.insert("dicsynth:sensor", Imf::StringAttribute(sensor->description));
  useAllCoresForExr();

  try {
    DescriptorOStream stream(file.duplicateFd(), file.tempPath());
    Imf::OutputFile out(stream, header);
    // Convert and write in bands of rows (exrBandRows): bounded memory for any image size, and
    // several zip blocks per call (16 rows each) to keep the cores compressing. 64 rows measured
    // fastest on 2 cores (Figure 1: 16 and 32 rows left cores idle, 256 and the whole image were
    // slower; bench/RESULTS.md). Every channel is 4 bytes. A row of the band is channelCount runs
    // of `width` words, one per channel, the order of a scanline in the file: OpenEXR copies each run in one sweep (pixels
    // interleaved, 80-byte strides for Figure 1's 20 channels, made the write phase 0.02 s longer:
    // bench/RESULTS.md, "Truth without copies"). The band's rows are converted on all cores.
    const int bandRows = exrBandRows();
    const std::size_t rowWords = std::size_t(width) * std::size_t(channelCount);
    const std::size_t rowBytes = sizeof(std::uint32_t) * rowWords;
    std::vector<std::uint32_t> band(rowWords * bandRows);
    for (int y0 = 0; y0 < image.height_px; y0 += bandRows) {
      const int y1 = std::min(image.height_px, y0 + bandRows);
      const std::size_t first = std::size_t(y0) * std::size_t(width);
      // Rows of the band on all cores, each thread all channels of its rows (no shared cache lines).
      parallelFor(std::size_t(y1 - y0), [&](std::size_t row) {
        for (std::size_t c = 0; c < channels.size(); ++c)
          channels[c].fill(first + row * std::size_t(width), std::size_t(width),
                           band.data() + row * rowWords + c * std::size_t(width), 1);
      });
      // The slices' base is where pixel (0, 0) would be: band row 0 is image row y0.
      char* base = reinterpret_cast<char*>(band.data()) - std::ptrdiff_t(y0) * std::ptrdiff_t(rowBytes);
      Imf::FrameBuffer frameBuffer;
      for (std::size_t c = 0; c < channels.size(); ++c) {
        frameBuffer.insert(channels[c].name,
                           Imf::Slice(channels[c].uintValue ? Imf::UINT : Imf::FLOAT,
                                      base + sizeof(std::uint32_t) * c * std::size_t(width), sizeof(std::uint32_t),
                                      rowBytes));
      }
      out.setFrameBuffer(frameBuffer);
      out.writePixels(y1 - y0);
    }
  } catch (const std::exception& e) {
    throw Error(path + ": cannot write EXR: " + e.what());
  }
}

}  // namespace

std::vector<ChannelValues> groundTruthChannels(const CameraImage& image, const DerivedTruth* truth,
                                               const SensorImage* sensor, const LayerSet& layers) {
  const std::size_t n = image.pixelCount();
  std::vector<ChannelValues> out;
  for (const ExrChannel& c : exrChannels(image, truth, sensor, layers)) {
    ChannelValues v;
    v.name = c.name;
    v.isUint = c.uintValue;
    // The very conversion the EXR writer runs: 32-bit words, float32 or uint32 by channel.
    std::vector<std::uint32_t> words(n);
    c.fill(0, n, words.data(), 1);
    if (v.isUint) {
      v.uints = std::move(words);
    } else {
      v.floats.resize(n);
      std::memcpy(v.floats.data(), words.data(), n * sizeof(float));
    }
    out.push_back(std::move(v));
  }
  return out;
}

OutputFiles writeCameraOutputs(const std::string& dir, const std::string& stem, const Camera& camera,
                               const CameraImage& image, const std::vector<std::uint16_t>& digital,
                               const OutputInfo& info, const DerivedTruth* truth, const SensorImage* sensor) {
  // Consistency of the caller's data: a mismatch is a bug upstream, not a user error.
  const std::size_t n = image.pixelCount();
  DS_CHECK(image.width_px == camera.width_px && image.height_px == camera.height_px && n > 0,
           "camera " + camera.name + ": image size differs from the camera's");
  DS_CHECK(image.radiance.size() == n && image.objectId.size() == n && digital.size() == n,
           "camera " + camera.name + ": a layer has the wrong pixel count");
  for (std::size_t size : {image.depth_m.size(), image.position_m.size(), image.normal.size(), image.uv.size()})
    DS_CHECK(size == 0 || size == n, "camera " + camera.name + ": a geometry layer has the wrong pixel count");
  if (truth) {
    for (std::size_t size : {truth->displacement_m.size(), truth->flow_px.size(), truth->flowMask.size(),
                             truth->disparity_px.size(), truth->disparityMask.size(), truth->distortion().size(),
                             truth->fieldError_m.size()})
      DS_CHECK(size == 0 || size == n, "camera " + camera.name + ": a derived layer has the wrong pixel count");
  }
  if (sensor) {
    for (std::size_t size : {sensor->noiseFree_DN.size(), sensor->noise_DN.size(), sensor->defects.size()})
      DS_CHECK(size == 0 || size == n, "camera " + camera.name + ": a sensor layer has the wrong pixel count");
  }
  DS_CHECK(!stem.empty() && stem.find('/') == std::string::npos, "output stem '" + stem + "'");

  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw Error("output folder '" + dir + "' does not exist or is not a folder");

  const std::vector<ExrChannel> channels = exrChannels(image, truth, sensor, info.layers);
  const bool tiffWanted = info.layers.has(Layer::Image), exrWanted = !channels.empty();
  OutputFiles files;
  if (tiffWanted) files.image = (std::filesystem::path(dir) / (stem + ".tif")).string();
  if (exrWanted) files.groundTruth = (std::filesystem::path(dir) / (stem + ".exr")).string();

  // Write both to temporary files first, then rename both: a failure while writing leaves neither.
  std::optional<AtomicFile> tiff, exr;
  if (tiffWanted) tiff.emplace(files.image);
  if (exrWanted) exr.emplace(files.groundTruth);
  const auto writeTiff = [&] {
    writeGrayTiff(*tiff, camera.width_px, camera.height_px, digital, camera.bitsPerPixel, tiffDescription(camera, info));
  };
  // With both, the TIFF is written on its own thread beside the EXR: libtiff deflates its strips one
  // after the other (0.02–0.04 s for 1600 × 1200; bench/RESULTS.md, "Truth without copies"), time
  // in which the EXR's thread pool and its writing thread go on. Both finish (or fail) before either
  // is renamed.
  std::future<void> tiffWritten;
  if (tiff && exr) tiffWritten = std::async(std::launch::async, writeTiff);
  else if (tiff) writeTiff();
  if (exr) {
    try {
      writeGroundTruthExr(*exr, camera, image, truth, sensor, info, channels);
    } catch (...) {
      if (tiffWritten.valid()) tiffWritten.wait();  // its file and buffers outlive it
      throw;
    }
  }
  if (tiffWritten.valid()) tiffWritten.get();  // rethrows the TIFF's error
  const auto hold = holdTermination();  // both renames, or a signal's cleanup first
  if (tiff) tiff->commit();
  try {
    if (exr) exr->commit();
  } catch (...) {
    // Only the second rename failed (rare: both live in one folder). Remove the TIFF so that no
    // image exists without its ground truth; an older EXR of the same name, if any, stays.
    std::error_code ignored;
    if (tiff) std::filesystem::remove(files.image, ignored);
    throw;
  }
  return files;
}

}  // namespace dicsynth
