#pragma once
// Prepared file textures kept across processes, so that start-up pays for a large texture once
// (decoding and B-spline prefiltering Figure 1's 4096×2048 texture: ~0.1 s on 2 cores; reading its
// 67 MB of coefficients back: bench/RESULTS.md, "Speed as a user times it").
// Key: the SHA-256 of the file's bytes (not its name or date: a copy of a texture on a cluster node
// hits, an edited one misses), the spline (interpolation and wrap), and the build ID of the code that prepared it
// (core/module_folder.h: any rebuild of the decoder or the prefilter invalidates every entry).
// Files: <cache folder>/textures/<digest>-<splineCode>-<build ID prefix>.bin, written atomically (core/atomic_file.h:
// concurrent writers each leave a complete file, the last rename wins), read with a check of the
// whole header and an Adler-32 of the coefficients, so a damaged, truncated or foreign file is
// ignored (and rewritten). The folder is kept under a size limit, least recently used first.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "geometry/prepared_scene.h"

namespace dicsynth {

class TextureDiskCache {
 public:
  // Textures smaller than this are prepared in a few milliseconds: not worth a file.
  static constexpr std::uint64_t kMinTexels = std::uint64_t(1) << 20;
  // The default size limit of the textures folder: ~15 textures of Figure 1's size.
  static constexpr std::uint64_t kDefaultLimitMiB = 1024;

  // folder: the cache folder (core/cache_dir.h), "" for none; limitBytes: the textures folder's
  // size limit, 0 for no disk cache.
  TextureDiskCache(std::string folder, std::uint64_t limitBytes);
  // The cache of the user's cache folder, its limit from $DICSYNTH_TEXTURE_CACHE_MB (MiB; 0 turns
  // it off) or kDefaultLimitMiB.
  static TextureDiskCache fromEnvironment();

  bool enabled() const { return !folder_.empty(); }
  const std::string& folder() const { return folder_; }  // .../textures, "" when disabled

  // The SHA-256 of `bytes` (a file's content, files/file_bytes.h) in hex; "" when OpenSSL fails.
  static std::string digestOf(std::string_view bytes);

  // The texture prepared from content `digest` with `interpolation` and `wrap`, when a valid file holds it
  // (its path set to `path`); marks the file recently used.
  std::optional<PreparedTexture> find(const std::string& digest, const std::string& path,
                                      Interpolation interpolation, TextureWrap wrap) const;
  // Stores `texture` (prepared from content `digest`) when it is large enough, then trims the
  // folder to the limit. Never throws: a failure prints one warning line and is otherwise ignored.
  void store(const std::string& digest, const PreparedTexture& texture) const noexcept;

 private:
  std::string fileFor(const std::string& digest, int splineCode) const;
  void trim(const std::string& keep) const;
  std::string folder_;
  std::uint64_t limitBytes_ = 0;
};

}  // namespace dicsynth
