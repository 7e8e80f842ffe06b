#pragma once
// The options every bench program takes: --spp N, --downscale K, --repeat R, and --scene FILE for
// the programs that render a scene of the user's choice. Unknown options are an error (exit 2).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace dicsynth::bench {

struct BenchArgs {
  int spp = 0, downscale = 0, repeat = 0;  // the program's defaults, overwritten by the options
  std::string scenePath;                   // empty: the program takes no --scene
};

// Reads the options into `args` (which holds the defaults). False, after naming the offending
// option on stderr, for an option the program does not take.
inline bool parseBenchArgs(int argc, char** argv, BenchArgs& args) {
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!args.scenePath.empty() && !std::strcmp(argv[i], "--scene")) args.scenePath = argv[i + 1];
    else if (!std::strcmp(argv[i], "--spp")) args.spp = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--downscale")) args.downscale = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeat")) args.repeat = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return false;
    }
  }
  return true;
}

}  // namespace dicsynth::bench
