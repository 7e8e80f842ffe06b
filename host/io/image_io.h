#pragma once
// Image files through OpenImageIO.
#include <cstdint>
#include <string>
#include <vector>

namespace dicsynth {

// A single-channel image, row-major, top row first.
struct GrayImage {
  int width = 0, height = 0;
  std::vector<double> pixels;
  double at(int x, int y) const { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

// Reads any format OIIO reads. Integer formats map to [0, 1] (value / max); float formats as stored.
// RGB(A) → Rec. 709 luminance of the linear values as stored (alpha ignored); 2 channels → first.
// Throws InputError("PATH: reason") when the file is missing, unreadable or empty.
GrayImage readGrayImage(const std::string& path);

// Writes a single-channel TIFF (8-bit when bits <= 8, else 16-bit) of raw values, atomically.
// `description` goes to the TIFF ImageDescription tag. Throws Error on I/O failure.
void writeGrayTiff(const std::string& path, int width, int height,
                   const std::vector<std::uint16_t>& values, int bits, const std::string& description);

}  // namespace dicsynth
