#include "geometry/texture_disk_cache.h"

#include <libdeflate.h>
#include <openssl/evp.h>
#include <unistd.h>
#include <zlib.h>  // adler32_combine64

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>
#include <vector>

#include "core/atomic_file.h"
#include "core/cache_dir.h"
#include "core/cache_file.h"
#include "core/env_count.h"
#include "core/error.h"
#include "core/hex.h"
#include "core/module_folder.h"
#include "core/parallel.h"
#include "core/warning.h"

namespace dicsynth {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'d', 's', 't', 'e', 'x', 't', 'r', 'c'};
constexpr std::uint32_t kFormat = 1;
constexpr std::uint32_t kByteOrder = 0x01020304;  // as this machine writes it

struct FileHeader {
  char magic[8];
  std::uint32_t format;
  std::uint32_t byteOrder;
  std::uint32_t spline;  // splineCode (texture/bspline.h): interpolation and wrap
  std::uint32_t width, height;
  std::uint32_t adler;  // Adler-32 of the coefficients' bytes
  std::uint64_t count;  // coefficients (doubles) after the header
  char digest[64];      // SHA-256 of the texture file, hex
  char buildId[64];     // the writing code's build ID, hex, zero-padded
};
static_assert(sizeof(FileHeader) == 8 + 6 * 4 + 8 + 64 + 64);

// Adler-32 of the coefficients' bytes, computed in pieces on all cores and combined in order
// (zlib's adler32_combine: the same value as one pass). One pass of zlib's adler32 took ~35 ms for
// Figure 1's 67 MB on this 2-core machine, about half of the prepare phase on a hit (0.079 s;
// 0.062 s in pieces); libdeflate's (SIMD) takes 7 ms where zlib's takes 43 ms (same value: the
// checksum is defined by RFC 1950, and the files of either stay valid).
std::uint32_t adlerOf(const std::vector<double>& values) {
  const auto* bytes = reinterpret_cast<const Bytef*>(values.data());
  const std::size_t total = values.size() * sizeof(double), piece = std::size_t(8) << 20;
  const std::size_t pieces = std::max<std::size_t>(1, (total + piece - 1) / piece);
  std::vector<uLong> sums(pieces);
  parallelFor(pieces, [&](std::size_t i) {
    const std::size_t begin = i * piece, length = std::min(piece, total - std::min(total, begin));
    sums[i] = libdeflate_adler32(1, bytes + begin, length);  // 1: Adler-32's initial value
  });
  uLong sum = sums[0];
  for (std::size_t i = 1; i < pieces; ++i)
    sum = adler32_combine64(sum, sums[i], z_off64_t(std::min(piece, total - i * piece)));
  return std::uint32_t(sum);
}

void copyText(char (&field)[64], const std::string& text) {
  std::memset(field, 0, sizeof field);
  std::memcpy(field, text.data(), std::min(text.size(), sizeof field));
}

bool sameText(const char (&field)[64], const std::string& text) {
  char expected[64];
  copyText(expected, text);
  return text.size() <= sizeof field && std::memcmp(field, expected, sizeof field) == 0;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

}  // namespace

TextureDiskCache::TextureDiskCache(std::string folder, std::uint64_t limitBytes) : limitBytes_(limitBytes) {
  // Without a build ID nothing could tell this code's files from another build's: no cache.
  if (folder.empty() || limitBytes == 0 || codeBuildId().empty() || codeBuildId().size() > 64) return;
  folder_ = (fs::path(folder) / "textures").string();
}

TextureDiskCache TextureDiskCache::fromEnvironment() {
  // At most 2^30 MiB (a pebibyte), so that the limit in bytes fits 64 bits; a negative value, which
  // strtoull would have wrapped to a huge one, is refused as well.
  const std::uint64_t limitMiB =
      std::uint64_t(envCount("DICSYNTH_TEXTURE_CACHE_MB", long(kDefaultLimitMiB), 0, 1L << 30));
  return TextureDiskCache(resolveCacheDir(""), limitMiB << 20);
}

std::string TextureDiskCache::digestOf(std::string_view bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1) return "";
  return hexString({digest, length});
}

std::string TextureDiskCache::fileFor(const std::string& digest, int spline) const {
  // The build in the name too: the CLI and the Python module (two binaries) keep their own files
  // instead of overwriting each other's on every alternation.
  return folder_ + "/" + digest + "-" + std::to_string(spline) + "-" + codeBuildId().substr(0, 16) + ".bin";
}

std::optional<PreparedTexture> TextureDiskCache::find(const std::string& digest, const std::string& path,
                                                      Interpolation interpolation, TextureWrap wrap) const {
  if (!enabled() || digest.empty()) return std::nullopt;
  const int spline = splineCode(interpolation, wrap);
  const std::string file = fileFor(digest, spline);
  // A regular file no larger than the folder may hold (core/cache_file.h: a FIFO there waited
  // forever, the cache audit of 2026-11-28).
  const std::optional<CacheFileHandle> handle = openCacheFile(file, limitBytes_);
  if (!handle) return std::nullopt;
  File in(::fdopen(handle->fd, "rb"));
  if (!in) {
    ::close(handle->fd);
    return std::nullopt;
  }
  FileHeader h{};
  if (std::fread(&h, sizeof h, 1, in.get()) != 1 || std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 ||
      h.format != kFormat || h.byteOrder != kByteOrder || h.spline != std::uint32_t(spline) ||
      !sameText(h.digest, digest) || !sameText(h.buildId, codeBuildId()) || h.width == 0 || h.height == 0 ||
      h.count != std::uint64_t(h.width) * h.height)
    return std::nullopt;
  std::error_code ec;
  if (handle->bytes != sizeof h + h.count * sizeof(double)) return std::nullopt;
  auto values = std::make_shared<std::vector<double>>(h.count);
  if (std::fread(values->data(), sizeof(double), h.count, in.get()) != h.count || adlerOf(*values) != h.adler)
    return std::nullopt;
  fs::last_write_time(file, fs::file_time_type::clock::now(), ec);  // recently used (trim keeps it)
  PreparedTexture t;
  t.path = path;
  t.width = int(h.width);
  t.height = int(h.height);
  t.interpolation = interpolation;
  t.wrap = wrap;
  t.coefficients = std::move(values);
  return t;
}

void TextureDiskCache::store(const std::string& digest, const PreparedTexture& texture) const noexcept {
  if (!enabled() || digest.empty() || texture.values().size() < kMinTexels) return;
  // A texture larger than the whole limit is not kept: trimming keeps the file just written, and
  // the folder held 67 MB under a 10 MiB limit (the cache audit of 2026-11-28).
  if (sizeof(FileHeader) + texture.values().size() * sizeof(double) > limitBytes_) return;
  const int spline = splineCode(texture.interpolation, texture.wrap);
  const std::string file = fileFor(digest, spline);
  try {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (ec) throw Error("cannot create " + folder_ + ": " + ec.message());
    FileHeader h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.format = kFormat;
    h.byteOrder = kByteOrder;
    h.spline = std::uint32_t(spline);
    h.width = std::uint32_t(texture.width);
    h.height = std::uint32_t(texture.height);
    h.count = texture.values().size();
    h.adler = adlerOf(texture.values());
    copyText(h.digest, digest);
    copyText(h.buildId, codeBuildId());
    AtomicFile atomic(file);
    {
      const int fd = atomic.duplicateFd();
      File out(::fdopen(fd, "wb"));
      if (!out) {
        ::close(fd);
        throw Error("cannot write " + atomic.tempPath());
      }
      const bool written = std::fwrite(&h, sizeof h, 1, out.get()) == 1 &&
                           std::fwrite(texture.values().data(), sizeof(double), h.count, out.get()) == h.count;
      if (!written || std::fclose(out.release()) != 0) throw Error("cannot write " + atomic.tempPath() + " completely");
    }
    atomic.commit();
    trim(file);
  } catch (const std::exception& e) {
    warn(std::string("texture cache: ") + e.what() + " (the texture is prepared again next time)");
  }
}

void TextureDiskCache::trim(const std::string& keep) const {
  // Other processes' temporaries are theirs until renamed, even when their process is not on this
  // machine (a cache folder in a home shared by cluster nodes): only those untouched for an hour
  // are a killed run's.
  removeStaleTemporaries(folder_, kCacheTemporaryAge);
  struct Entry {
    fs::file_time_type used;
    std::uint64_t bytes;
    fs::path path;
  };
  std::vector<Entry> entries;
  std::uint64_t total = 0;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec)) {
    // Not the temporaries (".<name>.tmp<pid>_<n>.bin", core/atomic_file.h) that other processes are
    // writing: trimming removed them and their rename failed (4 of 30 concurrent runs).
    if (e.path().extension() != ".bin" || e.path().filename().string().front() == '.' || !e.is_regular_file(ec))
      continue;
    const std::uint64_t bytes = e.file_size(ec);
    const fs::file_time_type used = e.last_write_time(ec);
    if (ec) continue;
    entries.push_back({used, bytes, e.path()});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
  for (const Entry& e : entries) {
    if (total <= limitBytes_) break;
    if (e.path == fs::path(keep)) continue;
    if (fs::remove(e.path, ec)) total -= e.bytes;  // another process may have removed it first
  }
}

}  // namespace dicsynth
