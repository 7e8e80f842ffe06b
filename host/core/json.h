#pragma once
// Minimal JSON output (the CLI's --json modes): string escaping and numbers that round-trip.
#include <cmath>
#include <cstdio>
#include <string>

#include "core/exact_number.h"

namespace dicsynth::json {

inline std::string quote(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += char(c);
        }
    }
  }
  return out + "\"";
}

// Exact (core/exact_number.h); JSON has no NaN/Infinity, so those become null.
inline std::string number(double v) { return std::isfinite(v) ? exactNumber(v) : "null"; }

inline std::string boolean(bool b) { return b ? "true" : "false"; }

}  // namespace dicsynth::json
