// Gray images through OpenImageIO: any readable format in, single-channel TIFF out.
#include "io/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "core/error.h"
#include "core/math.h"
#include "core/version.h"
#include "io/atomic_file.h"

namespace dicsynth {
namespace {

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

}  // namespace

GrayImage readGrayImage(const std::string& path) {
  // Check the commonest failures ourselves: OIIO's wording for them varies between formats.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a folder, not an image");

  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot read image: " + oneLine(OIIO::geterror()));
  const OIIO::ImageSpec spec = in->spec();  // subimage 0, MIP level 0
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw InputError(path + ": the image is empty");
  if (spec.depth > 1) throw InputError(path + ": volume images are not supported");

  // Channels used: 1 → itself, 2 → the first (gray + alpha), ≥ 3 → the first three as RGB.
  const int nchannels = spec.nchannels >= 3 ? 3 : 1;
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
  if (!ok || !problem.empty()) throw InputError(path + ": cannot read pixels: " + oneLine(problem));
  in->close();

  GrayImage image;
  image.width = spec.width;
  image.height = spec.height;
  if (nchannels == 1) {
    image.pixels = std::move(values);
  } else {
    image.pixels.resize(npixels);
    for (std::size_t i = 0; i < npixels; ++i)
      image.pixels[i] = luminance(dvec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]));
  }
  return image;
}

void writeGrayTiff(AtomicFile& file, int width, int height, const std::vector<std::uint16_t>& values,
                   int bits, const std::string& description) {
  const std::string& path = file.finalPath();
  DS_CHECK(width >= 1 && height >= 1, path + ": image size must be at least 1x1");
  DS_CHECK(values.size() == std::size_t(width) * std::size_t(height), path + ": pixel count");
  DS_CHECK(bits >= 1 && bits <= 16, path + ": bits must be in 1..16");
  const std::uint32_t maxValue = (1u << bits) - 1u;
  DS_CHECK(values.empty() || *std::max_element(values.begin(), values.end()) <= maxValue,
           path + ": a value exceeds 2^bits - 1");

  // Created by format name: the temporary file's name must not decide the format.
  auto out = OIIO::ImageOutput::create("tiff");
  if (!out) throw Error(path + ": OpenImageIO has no TIFF writer: " + oneLine(OIIO::geterror()));
  const bool eightBit = bits <= 8;
  OIIO::ImageSpec spec(width, height, 1, eightBit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
  spec.attribute("ImageDescription", description);
  spec.attribute("Software", std::string("dicsynth ") + kVersion);
  spec.attribute("compression", "zip");
  spec.attribute("DateTime", "");  // an empty DateTime makes OIIO omit the tag: reproducible files
  if (!out->open(file.tempPath(), spec))
    throw Error(path + ": cannot create TIFF: " + oneLine(out->geterror()));

  bool ok = false;
  if (eightBit) {
    // Narrow ourselves: OIIO's UINT16 → UINT8 conversion would rescale (65535 → 255).
    std::vector<std::uint8_t> narrow(values.begin(), values.end());
    ok = out->write_image(OIIO::TypeDesc::UINT8, narrow.data());
  } else {
    ok = out->write_image(OIIO::TypeDesc::UINT16, values.data());
  }
  if (!ok) throw Error(path + ": cannot write TIFF pixels: " + oneLine(out->geterror()));
  if (!out->close()) throw Error(path + ": cannot finish TIFF: " + oneLine(out->geterror()));
}

void writeGrayTiff(const std::string& path, int width, int height,
                   const std::vector<std::uint16_t>& values, int bits, const std::string& description) {
  AtomicFile file(path);
  writeGrayTiff(file, width, height, values, bits, description);
  file.commit();
}

}  // namespace dicsynth
