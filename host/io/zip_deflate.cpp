// zlib's compress2 for this process, done by libdeflate: the deflate behind every zip-compressed EXR.
//
// Why: OpenEXR 3.1 (Debian 12's) compresses each ZIP/ZIPS block (16 rows / 1 row) by zlib's
// compress2 at the header's zipCompressionLevel (1 in dicsynth). That zlib was ~1.2 CPU-s of
// Figure 1's default run, more than a quarter of the process on a 2-core lavapipe machine
// (bench/RESULTS.md, "Where lavapipe's render time goes"). libdeflate writes the same format (RFC
// 1950 zlib streams, Adler-32 included: any zlib reader decodes them to the same bytes) 2.1× faster
// at level 1 on Figure 1's 20 channels, and 0.6 % smaller (RESULTS.md, "zlib's compress2 by
// libdeflate"). Debian's libtiff already deflates with it; OpenEXR only from 3.2 on.
//
// How: a function the executable defines comes before a shared library's of the same name (ELF
// symbol interposition: the executable heads the global lookup scope, and the linker exports this
// definition because libOpenEXR refers to it; CMakeLists.txt names compress2 undefined for every
// program linking dicsynth_lib, so this file is always linked). So OpenEXR's calls, and any other library's
// compress2 in the process (VTK's XML writers), land here. Where the definition does not come first
// (the Python module, loaded into a python that links libz, writes no EXR anyway), zlib's stays:
// the same values, slower. zipDeflateEngine() says which one a process has.
//
// What libdeflate does not do as zlib would goes to zlib's own compress2 (dlsym RTLD_NEXT): levels
// other than 1..9 (zlib's -1 and 0 included), a failed allocation, and an output buffer libdeflate
// cannot fill (it needs a few bytes of slack; zlib then says Z_BUF_ERROR itself if the stream does
// not fit).
#include "io/zip_deflate.h"

#include <dlfcn.h>
#include <libdeflate.h>
#include <zlib.h>

#include <array>
#include <atomic>

namespace dicsynth {
namespace {

using Compress2 = int (*)(Bytef*, uLongf*, const Bytef*, uLong, int);

Compress2 zlibCompress2() {
  static const Compress2 next = reinterpret_cast<Compress2>(dlsym(RTLD_NEXT, "compress2"));
  return next;
}

// One compressor per thread and level: OpenEXR calls compress2 from all its pool's threads at once,
// and a libdeflate compressor holds state for one call at a time. Level 1's is ~0.5 MB.
struct ThreadCompressors {
  std::array<libdeflate_compressor*, 10> byLevel{};
  ~ThreadCompressors() {
    for (libdeflate_compressor* c : byLevel) libdeflate_free_compressor(c);  // accepts nullptr
  }
  libdeflate_compressor* get(int level) {
    if (!byLevel[level]) byLevel[level] = libdeflate_alloc_compressor(level);
    return byLevel[level];
  }
};

std::atomic<std::uint64_t> libdeflateCalls{0};  // relaxed: one increment per 16-row block

}  // namespace

std::uint64_t zipDeflateCalls() { return libdeflateCalls.load(std::memory_order_relaxed); }

std::string zipDeflateEngine() {
  const void* used = dlsym(RTLD_DEFAULT, "compress2");
  if (used == reinterpret_cast<const void*>(&::compress2)) return std::string("libdeflate ") + LIBDEFLATE_VERSION_STRING;
  return std::string("zlib ") + zlibVersion();
}

}  // namespace dicsynth

extern "C" int compress2(Bytef* dest, uLongf* destLen, const Bytef* source, uLong sourceLen, int level) {
  if (level >= 1 && level <= 9) {
    thread_local dicsynth::ThreadCompressors compressors;
    if (libdeflate_compressor* c = compressors.get(level)) {
      const std::size_t written = libdeflate_zlib_compress(c, source, sourceLen, dest, *destLen);
      if (written != 0) {
        *destLen = uLongf(written);
        dicsynth::libdeflateCalls.fetch_add(1, std::memory_order_relaxed);
        return Z_OK;
      }
    }
  }
  const dicsynth::Compress2 zlib = dicsynth::zlibCompress2();
  return zlib ? zlib(dest, destLen, source, sourceLen, level) : Z_STREAM_ERROR;
}
