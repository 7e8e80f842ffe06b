#pragma once
// File textures prepared once per process: a sweep renders the same texture at every point, and
// reading plus B-spline prefiltering a 4096×2048 texture costs about a second on this machine
// (bench/RESULTS.md, "Sweeps"). An entry is keyed by the path and the spline (the prefiltered
// coefficients depend on the kernel and the borders: texture/bspline.h splineCode) and checked against the file's stamp (core/file_stamp.h), so a
// texture edited during a run or between a Renderer's renders is read again. Optionally backed by
// a TextureDiskCache, which keeps large prepared textures across processes.
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "core/file_stamp.h"
#include "geometry/prepared_scene.h"
#include "geometry/texture_disk_cache.h"

namespace dicsynth {

class TextureCache {
 public:
  TextureCache() = default;
  explicit TextureCache(TextureDiskCache disk) : disk_(std::move(disk)) {}
  const TextureDiskCache& disk() const { return disk_; }

  // The prepared texture of `path` with `interpolation` and `wrap` when cached and the file is unchanged. It
  // shares the cached coefficient array (PreparedTexture::coefficients): nothing is copied.
  std::optional<PreparedTexture> find(const std::string& path, Interpolation interpolation, TextureWrap wrap) const {
    const auto stamp = fileStamp(path);
    std::lock_guard lock(mutex_);
    const auto it = entries_.find({path, splineCode(interpolation, wrap)});
    if (!stamp || it == entries_.end() || it->second.stamp != *stamp) return std::nullopt;
    return it->second.texture;
  }
  // Keyed by the stamp the texture was read under (PreparedTexture::stamp), not the file's stamp
  // now: a file replaced while it was decoded was stored as the new file's content, and a sweep
  // or a Python Renderer then rendered the old one until the process ended (the faults audit of
  // 2026-11-28: 12 of 12 Renderers).
  void insert(const PreparedTexture& texture) {
    std::lock_guard lock(mutex_);
    entries_[{texture.path, splineCode(texture.interpolation, texture.wrap)}] = {texture.stamp, texture};
  }
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return entries_.size();
  }

 private:
  struct Entry {
    FileStamp stamp;
    PreparedTexture texture;
  };
  TextureDiskCache disk_{"", 0};  // none unless given
  mutable std::mutex mutex_;  // a sweep prepares on a worker thread
  std::map<std::pair<std::string, int>, Entry> entries_;  // (path, splineCode)
};

}  // namespace dicsynth
