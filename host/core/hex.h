#pragma once
// Bytes as lowercase hexadecimal, two digits per byte: the names and keys of cache files (device
// UUIDs, SHA-256 digests, build IDs).
#include <span>
#include <string>

namespace dicsynth {

inline std::string hexString(std::span<const unsigned char> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * bytes.size());
  for (const unsigned char b : bytes) {
    hex += kDigits[b >> 4];
    hex += kDigits[b & 15];
  }
  return hex;
}

}  // namespace dicsynth
