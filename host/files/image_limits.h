#pragma once
// The size an input image may declare (Texture.File), checked from its header before any pixel
// buffer exists: a few hundred bytes of a compressed or header-only file can claim 20000 × 20000
// pixels (a "decompression bomb"). Header-only: used by the libtiff reader and by the OpenImageIO
// module (files/oiio_module/), which do not link the same libraries.
//
// Limits (docs/limits.md):
//  - at most kMaxImagePixels pixels (16384 × 16384): a texture samples a speckle a few texels per
//    image pixel, and 16k² already covers a 1600 × 1200 image at ten texels per pixel;
//  - the reading's peak memory, 8 bytes per pixel for the gray image (doubles) plus the reader's
//    buffer (8 bytes per channel per pixel), within the memory the system says is available.
#include <algorithm>
#include <cstdint>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "core/cgroup_limits.h"

namespace dicsynth {

inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(16384) * 16384;

// Bytes this process can still get: the system's (MemAvailable of /proc/meminfo), and no more than
// a control group's memory limit or `ulimit -v` leaves (core/cgroup_limits.h: a Slurm job's --mem
// on a large node passed every check and ended in std::bad_alloc); nullopt where none is known.
inline std::optional<std::uint64_t> availableMemoryBytes() {
  std::optional<std::uint64_t> available = processMemoryHeadroom();
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return available ? std::min(*available, kib * 1024) : kib * 1024;
  return available;
}

// "needs about X GiB, more than the Y GiB of memory available" when `bytes` exceed what the system
// can still give, else nullopt (also where that is unknown). For messages checked before a buffer
// exists: the image readers' below, `dicsynth speckle`'s.
inline std::optional<std::string> memoryShortfall(double bytes) {
  const auto available = availableMemoryBytes();
  if (!available || bytes <= double(*available)) return std::nullopt;
  std::ostringstream s;
  s.precision(3);
  s << "needs about " << bytes / (1 << 30) << " GiB, more than the " << double(*available) / (1 << 30)
    << " GiB of memory available";
  return s.str();
}

// Why a width × height image with `channels` channels (those the reader keeps) cannot be read, or
// nullopt when it can.
inline std::optional<std::string> imageSizeProblem(std::uint64_t width, std::uint64_t height, int channels) {
  const std::uint64_t pixels = width * height;  // both < 2^32: no overflow
  if (pixels > kMaxImagePixels)
    return "the image declares " + std::to_string(width) + " x " + std::to_string(height) + " = " +
           std::to_string(pixels) + " pixels, over the limit of " + std::to_string(kMaxImagePixels) +
           " (16384 x 16384)";
  const std::uint64_t bytes = pixels * 8 * (1 + std::uint64_t(channels));
  if (const auto shortfall = memoryShortfall(double(bytes)))
    return "reading the " + std::to_string(width) + " x " + std::to_string(height) + " image " + *shortfall;
  return std::nullopt;
}

}  // namespace dicsynth
