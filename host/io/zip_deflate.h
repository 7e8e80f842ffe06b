// Which deflate compresses this process's zip EXRs (io/zip_deflate.cpp defines zlib's compress2
// by libdeflate).
#pragma once

#include <cstdint>
#include <string>

namespace dicsynth {

// "libdeflate 1.14" where this binary's compress2 is the one the process calls, else "zlib 1.2.13"
// (e.g. in the Python module). `dicsynth --version` prints it.
std::string zipDeflateEngine();

// How many compress2 calls of this process libdeflate has answered (the rest went to zlib): tests
// use it to see that OpenEXR's blocks really come here.
std::uint64_t zipDeflateCalls();

}  // namespace dicsynth
