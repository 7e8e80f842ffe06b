// Gray images: common TIFFs through libtiff, any other readable format through OpenImageIO's
// module; single-channel TIFF out through libtiff.
#include "files/image_io.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"
#include "files/oiio_reader.h"
#include "files/tiff_io.h"

namespace dicsynth {

GrayImage readGrayImage(const std::string& path) {
  // Check the commonest failures ourselves: the readers' wording for them varies between formats.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a folder, not an image");
  // Devices and pipes are refused: reading /dev/zero as an image never ends.
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": not a regular file");
  if (looksLikeTiff(path))
    if (std::optional<GrayImage> image = readCommonTiff(path)) return std::move(*image);
  return readGrayImageWithOiio(path);
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

  writeGrayTiffFile(file.duplicateFd(), path, width, height, values, bits, description);
}

void writeGrayTiff(const std::string& path, int width, int height,
                   const std::vector<std::uint16_t>& values, int bits, const std::string& description) {
  AtomicFile file(path);
  writeGrayTiff(file, width, height, values, bits, description);
  file.commit();
}

}  // namespace dicsynth
