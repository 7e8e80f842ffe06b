// libdicsynth_oiio.so: readGrayImage for every format OpenImageIO reads (files/oiio_reader.h loads it
// on first use). Built as its own module so that the dicsynth binary does not link OpenImageIO.
#include "files/oiio_module/oiio_module.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <exception>

#include "core/math.h"
#include "files/image_limits.h"

namespace {

using dicsynth::GrayImage;

// OIIO's messages may span lines or end with one; ours are one line.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.empty() ? "unknown OpenImageIO error" : text;
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

bool readGray(const std::string& path, GrayImage& image, std::string& error) {
  // The stored values, alpha ignored, as the libtiff reader gives them: by default OpenImageIO
  // multiplies the colour of a file with unassociated alpha (PNG, TIFF with ExtraSamples = 2) by
  // it, so an RGBA PNG read half as bright as the same strip TIFF (the texture audit of 2026-11-28).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
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

extern "C" __attribute__((visibility("default"))) bool dicsynth_oiio_read_gray(const char* path, GrayImage* image,
                                                                               std::string* error) {
  try {
    return readGray(path, *image, *error);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for a huge declared size
    *error = std::string("cannot read image: ") + e.what();
    return false;
  }
}

// The signature the loader expects.
static_assert(std::is_same_v<decltype(&dicsynth_oiio_read_gray), dicsynth::ReadGrayFn>);
