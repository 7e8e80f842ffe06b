// libdicsynth_oiio.so: readGrayImage for every format OpenImageIO reads (files/oiio_reader.h loads it
// on first use). Built as its own module so that the dicsynth binary does not link OpenImageIO.
#include "files/oiio_module/oiio_module.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "files/image_limits.h"

namespace {

using dicsynth::GrayImage;

// OIIO's messages may span lines or end with one; ours are one line. A reader often reports one
// cause at several levels (a truncated PNG: "Read error: hit end of file", "PNG read error: IDAT:
// Read error: hit end of file", "PNG library error"): a line that another line contains is
// dropped, the rest joined by "; ".
std::string oneLine(const std::string& text) {
  std::vector<std::string> lines;
  for (std::string line : OIIO::Strutil::splits(text, "\n")) {
    line = std::string(OIIO::Strutil::strip(line));
    if (!line.empty()) lines.push_back(std::move(line));
  }
  std::string joined;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    bool repeated = false;  // contained in a longer line, or equal to an earlier one
    for (std::size_t j = 0; j < lines.size() && !repeated; ++j)
      repeated = j != i && lines[j].find(lines[i]) != std::string::npos && (lines[j].size() > lines[i].size() || j < i);
    if (!repeated) joined += (joined.empty() ? "" : "; ") + lines[i];
  }
  return joined.empty() ? "unknown OpenImageIO error" : joined;
}

// Reads `nchannels` channels of the first subimage as T and maps each value v to v / maxValue.
// Used for uint8/uint16 files so that v/255 and v/65535 are correctly rounded doubles: OIIO's own
// conversion to double goes through float (errors up to 3e-8 for uint16, measured).
template <typename T>
bool readNormalized(OIIO::ImageInput& in, int nchannels, OIIO::TypeDesc type, double maxValue,
                    std::vector<double>& out) {
  std::vector<T> raw(out.size());
  if (!in.read_image(0, 0, 0, nchannels, type, raw.data())) return false;
  for (std::size_t i = 0; i < raw.size(); ++i) out[i] = double(raw[i]) / maxValue;
  return true;
}

// The input formats OpenImageIO knows, the one the file's extension names first (the order in
// which ImageInput::open tries them).
std::vector<std::string> formatsToTry(const std::string& path) {
  using OIIO::Strutil::splits;
  std::vector<std::string> formats = splits(OIIO::get_string_attribute("input_format_list"), ",");
  const std::string extension = OIIO::Strutil::lower(OIIO::Filesystem::extension(path, false));
  // "extension_list": "tiff:tif,tiff,tx;png:png;..."
  for (const std::string& entry : splits(OIIO::get_string_attribute("extension_list"), ";")) {
    const std::size_t colon = entry.find(':');
    if (colon == std::string::npos || extension.empty()) continue;
    const std::vector<std::string> extensions = splits(entry.substr(colon + 1), ",");
    const auto format = std::find(formats.begin(), formats.end(), entry.substr(0, colon));
    if (format != formats.end() && std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) {
      std::rotate(formats.begin(), format, format + 1);
      break;
    }
  }
  return formats;
}

// An opened reader and the memory it reads (declared first: it must outlive the reader).
struct OpenedImage {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> in;
};

// Opens the file's bytes with the first format whose reader takes memory input
// (supports("ioproxy")) and accepts them. ImageInput::open(path, config, proxy) is not used: where
// a reader takes no proxy, OpenImageIO 2.4 ignores it and opens the path.
OpenedImage openBytes(const std::string& path, const char* bytes, std::size_t size, const OIIO::ImageSpec& config) {
  for (const std::string& format : formatsToTry(path)) {
    OpenedImage opened;
    opened.in = OIIO::ImageInput::create(format);  // a format's name: created, not opened or probed
    if (!opened.in || !opened.in->supports("ioproxy")) continue;
    opened.memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes, size);
    OIIO::ImageSpec spec;
    if (opened.in->set_ioproxy(opened.memory.get()) && opened.in->open(path, spec, config)) return opened;
    (void)opened.in->geterror();  // this format's complaint: not ours to report
  }
  (void)OIIO::geterror();
  return {};
}

bool readGray(const std::string& path, const char* bytes, std::size_t size, GrayImage& image, std::string& error,
              bool& readPath) {
  // The stored values, alpha ignored, as the libtiff reader gives them: by default OpenImageIO
  // multiplies the colour of a file with unassociated alpha (PNG, TIFF with ExtraSamples = 2) by
  // it, so an RGBA PNG read half as bright as the same strip TIFF (the texture audit of 2026-11-28).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OpenedImage opened = openBytes(path, bytes, size, config);
  readPath = !opened.in;
  // No reader took the bytes: a format read from files only, or bytes no format reads, which
  // OpenImageIO's own search by the path then names.
  if (!opened.in) opened.in = OIIO::ImageInput::open(path, &config);
  OIIO::ImageInput* in = opened.in.get();
  if (!in) {
    error = "cannot read image: " + oneLine(OIIO::geterror());
    return false;
  }
  const OIIO::ImageSpec spec = in->spec();  // subimage 0, MIP level 0
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    error = "the image is empty";
    return false;
  }
  if (spec.depth > 1) {
    error = "volume images are not supported";
    return false;
  }
  // Channels used: 1 → itself, 2 → the first (gray + alpha), ≥ 3 → the first three as RGB.
  const int nchannels = spec.nchannels >= 3 ? 3 : 1;
  if (const auto problem = dicsynth::imageSizeProblem(std::uint64_t(spec.width), std::uint64_t(spec.height), nchannels)) {
    error = *problem;
    return false;
  }
  const std::size_t npixels = std::size_t(spec.width) * std::size_t(spec.height);
  std::vector<double> values(npixels * std::size_t(nchannels));
  const bool perChannelFormats = !spec.channelformats.empty();
  bool ok = false;
  if (!perChannelFormats && spec.format == OIIO::TypeDesc::UINT8) {
    ok = readNormalized<std::uint8_t>(*in, nchannels, OIIO::TypeDesc::UINT8, 255.0, values);
  } else if (!perChannelFormats && spec.format == OIIO::TypeDesc::UINT16) {
    ok = readNormalized<std::uint16_t>(*in, nchannels, OIIO::TypeDesc::UINT16, 65535.0, values);
  } else {
    ok = in->read_image(0, 0, 0, nchannels, OIIO::TypeDesc::DOUBLE, values.data());
  }
  // OIIO 2.4 reports some failures (a truncated TIFF strip) only as a message, with ok == true.
  const std::string problem = in->geterror();
  if (!ok || !problem.empty()) {
    error = "cannot read pixels: " + oneLine(problem);
    return false;
  }
  in->close();
  image.width = spec.width;
  image.height = spec.height;
  if (nchannels == 1) {
    image.pixels = std::move(values);
  } else {
    image.pixels.resize(npixels);
    for (std::size_t i = 0; i < npixels; ++i)
      image.pixels[i] = dicsynth::luminance(dicsynth::dvec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]));
  }
  return true;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) bool dicsynth_oiio_read_gray(const char* path, const char* bytes,
                                                                               std::size_t size, GrayImage* image,
                                                                               std::string* error, bool* readPath) {
  try {
    return readGray(path, bytes, size, *image, *error, *readPath);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for a huge declared size
    *error = std::string("cannot read image: ") + e.what();
    return false;
  }
}

// The signature the loader expects.
static_assert(std::is_same_v<decltype(&dicsynth_oiio_read_gray), dicsynth::ReadGrayFn>);
