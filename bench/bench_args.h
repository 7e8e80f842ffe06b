#pragma once
// The options every bench program takes: --spp N, --downscale K, --repeat R (whole numbers >= 1),
// and --scene FILE for the programs that render a scene of the user's choice; and the guard of
// their main functions. A bad option, a missing value, a number that is not one or a scene that
// fails to load is one line on stderr and exit 2, a failure of the run exit 3, as dicsynth answers
// (the bench audit of 2026-11-28: `--spp abc` and `--scene /missing` aborted on an uncaught
// exception, a trailing `--spp` was ignored, `--repeat 0` printed 1e300 s and exited 0).
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "core/error.h"

namespace dicsynth::bench {

struct BenchArgs {
  int spp = 0, downscale = 0, repeat = 0;  // the program's defaults, overwritten by the options
  std::string scenePath;                   // empty: the program takes no --scene
};

// `text` as a whole number >= 1, or an InputError naming `option`.
inline int positiveCount(const char* option, const char* text) {
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || v < 1 || v > 1000000000)
    throw InputError(std::string(option) + " '" + text + "': expected a whole number >= 1");
  return int(v);
}

// Reads the options into `args` (which holds the defaults); `extra` names one more count option the
// program takes (e.g. "--points"), stored in *extraValue. Throws InputError naming the option that
// is unknown, lacks its value or has a bad one.
inline void parseBenchArgs(int argc, char** argv, BenchArgs& args, const char* extra = nullptr,
                           int* extraValue = nullptr) {
  for (int i = 1; i < argc; i += 2) {
    const char* option = argv[i];
    const bool known = (!args.scenePath.empty() && !std::strcmp(option, "--scene")) || !std::strcmp(option, "--spp") ||
                       !std::strcmp(option, "--downscale") || !std::strcmp(option, "--repeat") ||
                       (extra && !std::strcmp(option, extra));
    if (!known) throw InputError(std::string("unknown option ") + option);
    if (i + 1 >= argc) throw InputError(std::string(option) + " needs a value");
    const char* value = argv[i + 1];
    if (!std::strcmp(option, "--scene")) args.scenePath = value;
    else if (!std::strcmp(option, "--spp")) args.spp = positiveCount(option, value);
    else if (!std::strcmp(option, "--downscale")) args.downscale = positiveCount(option, value);
    else if (!std::strcmp(option, "--repeat")) args.repeat = positiveCount(option, value);
    else *extraValue = positiveCount(option, value);
  }
}

// Runs a bench program's body: an InputError is one line on stderr and exit 2, any other error
// exit 3.
template <class Body>
int guarded(Body body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  }
}

}  // namespace dicsynth::bench
