#pragma once
// Numbers in output files: 17 significant digits ("%.17g"), so every double reads back exactly,
// written by std::to_chars, which unlike printf ignores the C locale (a decimal comma would break
// every reader).
#include <charconv>
#include <string>

namespace dicsynth {

inline std::string exactNumber(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  return std::string(buffer, result.ptr);
}

// exactNumber, with a zero written "0", never "-0" (a camera at the origin: t = -R C; R's zero
// entries after a product): the same value for every reader, and what a person expects to read.
// For calibration files and headers; not for keys, whose text must stay as earlier runs wrote it.
inline std::string exactNumberPlainZero(double value) { return exactNumber(value == 0 ? 0.0 : value); }

// The shortest text that reads back as the same double ("0.04", "-3", "inf", "nan"): for messages.
// A NaN is "nan" whatever its sign bit (Lua's 0/0 is a negative NaN on x86: "-nan" reads as a
// number that is negative).
inline std::string shortestNumber(double value) {
  if (value != value) return "nan";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace dicsynth
