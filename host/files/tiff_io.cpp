#include "files/tiff_io.h"

#include "files/image_limits.h"

#include <tiffio.h>
#include <unistd.h>

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.h"
#include "core/math.h"
#include "core/version.h"

namespace dicsynth {
namespace {

// libtiff reports through process-wide handlers; the text of the last error of this thread is kept
// for the exception (two threads may read or write TIFFs at once: a sweep's writer and its next
// point's texture).
thread_local std::string tLastTiffError;

void onTiffError(const char* module, const char* format, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  tLastTiffError = (module && *module ? std::string(module) + ": " : std::string()) + text;
}
void onTiffWarning(const char*, const char*, va_list) {}  // unknown tags and the like: not ours to report

void installHandlers() {
  static const bool once = [] {
    TIFFSetErrorHandler(onTiffError);
    TIFFSetWarningHandler(onTiffWarning);
    return true;
  }();
  (void)once;
}

std::string lastError() {
  std::string e = tLastTiffError.empty() ? "libtiff gave no reason" : tLastTiffError;
  tLastTiffError.clear();
  return e;
}

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
using TiffPtr = std::unique_ptr<TIFF, TiffCloser>;

template <class T>
T field(TIFF* tif, ttag_t tag, T fallback) {
  T value = fallback;
  return TIFFGetFieldDefaulted(tif, tag, &value) == 1 ? value : fallback;
}

}  // namespace

bool looksLikeTiff(std::string_view bytes) {
  if (bytes.size() < 4) return false;
  const auto magic = [&](int i) { return static_cast<unsigned char>(bytes[std::size_t(i)]); };
  const bool little = magic(0) == 'I' && magic(1) == 'I' && (magic(2) == 42 || magic(2) == 43) && magic(3) == 0;
  const bool big = magic(0) == 'M' && magic(1) == 'M' && magic(2) == 0 && (magic(3) == 42 || magic(3) == 43);
  return little || big;
}

namespace {

// libtiff reads the bytes in memory through its client interface: a read-only stream over them.
struct MemoryStream {
  std::string_view bytes;
  std::uint64_t position = 0;
};

tmsize_t memoryRead(thandle_t handle, void* buffer, tmsize_t size) {
  auto* s = static_cast<MemoryStream*>(handle);
  if (size < 0 || s->position >= s->bytes.size()) return 0;
  const std::uint64_t n = std::min<std::uint64_t>(std::uint64_t(size), s->bytes.size() - s->position);
  std::memcpy(buffer, s->bytes.data() + s->position, n);
  s->position += n;
  return tmsize_t(n);
}
tmsize_t memoryWrite(thandle_t, void*, tmsize_t) { return -1; }  // opened for reading only
toff_t memorySeek(thandle_t handle, toff_t offset, int whence) {
  auto* s = static_cast<MemoryStream*>(handle);
  // toff_t is unsigned: a negative relative offset arrives as its two's complement, which the
  // unsigned sum wraps back.
  const std::uint64_t base = whence == SEEK_CUR ? s->position : whence == SEEK_END ? s->bytes.size() : 0;
  const std::uint64_t target = base + std::uint64_t(offset);
  if (target > std::uint64_t(INT64_MAX)) return toff_t(-1);
  s->position = target;  // past the end: later reads return 0 (a damaged offset), as a file's would
  return toff_t(target);
}
int memoryClose(thandle_t) { return 0; }
toff_t memorySize(thandle_t handle) { return toff_t(static_cast<MemoryStream*>(handle)->bytes.size()); }
// No mapping: libtiff reads strips through memoryRead (its "mapped" path would hand it our buffer,
// which it must not write; reading copies only a strip at a time).
int memoryMap(thandle_t, void**, toff_t*) { return 0; }
void memoryUnmap(thandle_t, void*, toff_t) {}

}  // namespace

std::optional<GrayImage> readCommonTiff(const std::string& path, std::string_view bytes) {
  installHandlers();
  tLastTiffError.clear();
  MemoryStream stream{bytes};
  TiffPtr tif(TIFFClientOpen(path.c_str(), "rm", &stream, memoryRead, memoryWrite, memorySeek, memoryClose,
                             memorySize, memoryMap, memoryUnmap));
  if (!tif) throw InputError(path + ": cannot read image: " + lastError());
  TIFF* t = tif.get();
  const std::uint32_t width = field<std::uint32_t>(t, TIFFTAG_IMAGEWIDTH, 0);
  const std::uint32_t height = field<std::uint32_t>(t, TIFFTAG_IMAGELENGTH, 0);
  const std::uint16_t bits = field<std::uint16_t>(t, TIFFTAG_BITSPERSAMPLE, 1);
  const std::uint16_t samples = field<std::uint16_t>(t, TIFFTAG_SAMPLESPERPIXEL, 1);
  const std::uint16_t format = field<std::uint16_t>(t, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
  const std::uint16_t planar = field<std::uint16_t>(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  std::uint16_t photometric = 0;
  const bool hasPhotometric = TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photometric) == 1;
  const bool uintKind = format == SAMPLEFORMAT_UINT && (bits == 8 || bits == 16);
  const bool floatKind = format == SAMPLEFORMAT_IEEEFP && bits == 32;
  const bool gray = hasPhotometric && photometric == PHOTOMETRIC_MINISBLACK && samples <= 2;
  const bool rgb = hasPhotometric && photometric == PHOTOMETRIC_RGB && (samples == 3 || samples == 4);
  if (TIFFIsTiled(t) || !(uintKind || floatKind) || !(gray || rgb) || (samples > 1 && planar != PLANARCONFIG_CONTIG))
    return std::nullopt;  // OpenImageIO reads it
  if (width == 0 || height == 0) throw InputError(path + ": the image is empty");
  if (const auto problem = imageSizeProblem(width, height, 0)) throw InputError(path + ": " + *problem);

  // Channels used as readGrayImage says: 1 → itself, 2 → the first, 3 or 4 → Rec. 709 luminance.
  const std::size_t w = width, n = std::size_t(width) * std::size_t(height);
  GrayImage image;
  image.width = int(width);
  image.height = int(height);
  image.pixels.resize(n);
  std::vector<unsigned char> line(std::size_t(TIFFScanlineSize64(t)));
  const std::size_t bytesPerSample = bits / 8;
  if (line.size() < w * samples * bytesPerSample) throw InputError(path + ": inconsistent TIFF scanline size");
  auto sampleAt = [&](std::size_t x, std::size_t s) -> double {
    const unsigned char* p = line.data() + (x * samples + s) * bytesPerSample;
    if (floatKind) {
      float v;
      std::memcpy(&v, p, sizeof v);
      return v;
    }
    if (bits == 8) return double(p[0]) / 255.0;  // correctly rounded, as in the OpenImageIO path
    std::uint16_t v;
    std::memcpy(&v, p, sizeof v);  // libtiff hands samples in host byte order
    return double(v) / 65535.0;
  };
  for (std::uint32_t y = 0; y < height; ++y) {
    if (TIFFReadScanline(t, line.data(), y, 0) != 1 || !tLastTiffError.empty())
      throw InputError(path + ": cannot read pixels: " + lastError());
    double* row = image.pixels.data() + std::size_t(y) * w;
    if (gray) {
      for (std::size_t x = 0; x < w; ++x) row[x] = sampleAt(x, 0);
    } else {
      for (std::size_t x = 0; x < w; ++x) row[x] = luminance(dvec3(sampleAt(x, 0), sampleAt(x, 1), sampleAt(x, 2)));
    }
  }
  return image;
}

void writeGrayTiffFile(int fd, const std::string& finalPath, int width, int height,
                       const std::vector<std::uint16_t>& values, int bits, const std::string& description) {
  installHandlers();
  tLastTiffError.clear();
  TiffPtr tif(TIFFFdOpen(fd, finalPath.c_str(), "w"));  // TIFFClose closes fd
  if (!tif) {
    ::close(fd);
    throw Error(finalPath + ": cannot create TIFF: " + lastError());
  }
  TIFF* t = tif.get();
  const bool eightBit = bits <= 8;
  const std::uint32_t rowsPerStrip = 32;  // 32 rows per zip strip: ~100 KB of a 1600-px 16-bit image
  // Deflate level 1 (libtiff's default is 6), by libdeflate (whole strips, below): Figure 1's 10-bit
  // image is written in 0.021 s, 1.304 MB; level 2: 0.025 s, 1.336 MB; 6: 0.038 s, 1.328 MB; 9:
  // 0.133 s, 1.300 MB; 12: 0.32 s, 1.267 MB (bench/RESULTS.md, "Truth without copies"). The pixels
  // are the same at every level.
  const int kZipLevel = 1;
  const std::string software = std::string("dicsynth ") + kVersion;
  // No DateTime tag: the same pixels give the same file.
  const bool ok = TIFFSetField(t, TIFFTAG_IMAGEWIDTH, std::uint32_t(width)) == 1 &&
                  TIFFSetField(t, TIFFTAG_IMAGELENGTH, std::uint32_t(height)) == 1 &&
                  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, std::uint16_t(eightBit ? 8 : 16)) == 1 &&
                  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, std::uint16_t(1)) == 1 &&
                  TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, std::uint16_t(SAMPLEFORMAT_UINT)) == 1 &&
                  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, std::uint16_t(PHOTOMETRIC_MINISBLACK)) == 1 &&
                  TIFFSetField(t, TIFFTAG_PLANARCONFIG, std::uint16_t(PLANARCONFIG_CONTIG)) == 1 &&
                  TIFFSetField(t, TIFFTAG_COMPRESSION, std::uint16_t(COMPRESSION_ADOBE_DEFLATE)) == 1 &&
                  TIFFSetField(t, TIFFTAG_PREDICTOR, std::uint16_t(PREDICTOR_HORIZONTAL)) == 1 &&
                  TIFFSetField(t, TIFFTAG_ZIPQUALITY, kZipLevel) == 1 &&
                  TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, rowsPerStrip) == 1 &&
                  TIFFSetField(t, TIFFTAG_IMAGEDESCRIPTION, description.c_str()) == 1 &&
                  TIFFSetField(t, TIFFTAG_SOFTWARE, software.c_str()) == 1;
  if (!ok) throw Error(finalPath + ": cannot set TIFF fields: " + lastError());
  // Whole strips (TIFFWriteEncodedStrip), not scanlines: libtiff deflates a strip given at once with
  // libdeflate, and row by row with zlib's stream (Figure 1: 0.021 against 0.036 s, 6 % smaller;
  // bench/RESULTS.md, "Truth without copies"). The pixels are the same either way.
  const std::size_t w = std::size_t(width), bytesPerSample = eightBit ? 1 : 2;
  std::vector<std::uint8_t> strip(w * rowsPerStrip * bytesPerSample);
  for (int y0 = 0, index = 0; y0 < height; y0 += int(rowsPerStrip), ++index) {
    const int rows = std::min(height - y0, int(rowsPerStrip));
    const std::uint16_t* src = values.data() + std::size_t(y0) * w;
    const std::size_t count = std::size_t(rows) * w;
    if (eightBit) {
      for (std::size_t i = 0; i < count; ++i) strip[i] = std::uint8_t(src[i]);  // < 2^bits ≤ 256: exact
    } else {
      std::memcpy(strip.data(), src, count * 2);  // libtiff encodes the strip in place (predictor)
    }
    if (TIFFWriteEncodedStrip(t, std::uint32_t(index), strip.data(), tmsize_t(count * bytesPerSample)) < 0)
      throw Error(finalPath + ": cannot write TIFF pixels: " + lastError());
  }
  if (TIFFFlush(t) != 1) throw Error(finalPath + ": cannot finish TIFF: " + lastError());
}

}  // namespace dicsynth
