#pragma once
// TIFF through libtiff directly: the sensor images dicsynth writes and the plain TIFF textures it
// reads most, without OpenImageIO, whose ~250 shared libraries cost every process ~0.18 s of
// dynamic linking at start (docs/performance.md). Other formats and unusual TIFF
// variants go through OpenImageIO, loaded only when needed (files/oiio_reader.h).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "files/image_io.h"

namespace dicsynth {

// True when the bytes start with a TIFF header (II*\0 or MM\0*; BigTIFF included).
bool looksLikeTiff(std::string_view bytes);

// A TIFF of the common kinds, decoded from the file's bytes (files/file_bytes.h; `path` names it in
// messages): strips, 1 (gray), 2 (gray + alpha), 3 or 4 (RGB[A]) interleaved samples of 8 or 16
// bits unsigned or 32-bit float, gray or RGB. Values as readGrayImage documents. nullopt for any
// other kind (tiles, palettes, other bit depths, YCbCr, CMYK, ...): the caller reads it through
// OpenImageIO. Throws InputError("PATH: reason") for a damaged file.
std::optional<GrayImage> readCommonTiff(const std::string& path, std::string_view bytes);

// The single-channel zip-compressed TIFF of writeGrayTiff (files/image_io.h), written through the
// descriptor `fd` of an empty file (AtomicFile::duplicateFd), which it closes; errors name
// `finalPath`.
void writeGrayTiffFile(int fd, const std::string& finalPath, int width, int height,
                       const std::vector<std::uint16_t>& values, int bits, const std::string& description);

}  // namespace dicsynth
