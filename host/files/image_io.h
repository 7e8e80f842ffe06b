#pragma once
// Image files: TIFF through libtiff (files/tiff_io.h), other formats through OpenImageIO (files/oiio_reader.h).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dicsynth {

class AtomicFile;

// A single-channel image, row-major, top row first.
struct GrayImage {
  int width = 0, height = 0;
  std::vector<double> pixels;
  double at(int x, int y) const { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

// Reads any format OIIO reads (first subimage, full resolution). Integer formats map to [0, 1]
// (value / max; uint8 and uint16 exactly in double, others through OIIO's conversion); float formats
// as stored. 1 channel → itself; 2 channels (gray + alpha) → the first; 3 or more → Rec. 709
// luminance of the first three, taken as linear RGB as stored (alpha and further channels ignored).
// Throws InputError("PATH: reason") when the file is missing, unreadable or empty, or when it was
// written in place while it was read (files/file_bytes.h).
GrayImage readGrayImage(const std::string& path);

// The same from the file's bytes, read by the caller (files/file_bytes.h); `path` names the file in
// messages and its extension tells OpenImageIO the format to try first. Every decoder reads the
// bytes, except OpenImageIO's for the few formats whose reader takes no memory input (SGI, ICO,
// FITS, RLA, Cineon, Softimage, RAW, HEIF, ... in OpenImageIO 2.4): those read `path`, and
// `*readPath` (when given) is set to say so, for the caller to check that the file is still the one
// it read.
GrayImage decodeGrayImage(const std::string& path, std::string_view bytes, bool* readPath = nullptr);

// Writes a single-channel TIFF (8-bit when bits <= 8, else 16-bit) of raw values, atomically.
// `description` goes to the TIFF ImageDescription tag. Throws Error on I/O failure.
// Zip-compressed (lossless). Every value must be < 2^bits (bits in 1..16); values are never rescaled:
// a 10-bit image is a 16-bit TIFF whose values are < 1024. No DateTime tag is written, so the same
// pixels give the same file (byte for byte with the same libtiff/zlib).
void writeGrayTiff(const std::string& path, int width, int height,
                   const std::vector<std::uint16_t>& values, int bits, const std::string& description);

// The same, written to `file.tempPath()` and NOT committed: for writers that commit several files
// together (host/io/outputs.cpp).
void writeGrayTiff(AtomicFile& file, int width, int height, const std::vector<std::uint16_t>& values,
                   int bits, const std::string& description);

}  // namespace dicsynth
