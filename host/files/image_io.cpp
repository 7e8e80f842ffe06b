// Gray images: common TIFFs through libtiff, any other readable format through OpenImageIO's
// module; single-channel TIFF out through libtiff.
#include "files/image_io.h"

#include <algorithm>
#include <optional>

#include "core/atomic_file.h"
#include "core/error.h"
#include "files/file_bytes.h"
#include "files/oiio_reader.h"
#include "files/tiff_io.h"

namespace dicsynth {

GrayImage decodeGrayImage(const std::string& path, std::string_view bytes, bool* readPath) {
  if (readPath) *readPath = false;
  if (looksLikeTiff(bytes))
    if (std::optional<GrayImage> image = readCommonTiff(path, bytes)) return std::move(*image);
  return readGrayImageWithOiio(path, bytes, readPath);
}

GrayImage readGrayImage(const std::string& path) {
  // One reading: the retries of a file being written are the texture loader's (geometry/prepare.cpp),
  // which also keeps the bytes' stamp and CRC.
  const std::optional<FileBytes> file = readFileBytes(path);
  if (!file) throw InputError(path + ": the file changed while it was read: it is being written (read it once it is complete)");
  return decodeGrayImage(path, file->bytes);
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
