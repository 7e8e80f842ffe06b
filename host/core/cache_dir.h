#pragma once
// The folder of dicsynth's caches across processes (the Vulkan pipeline cache, per-device records,
// prepared textures).
#include <string>

namespace dicsynth {

// `option` when not empty, else $DICSYNTH_CACHE_DIR, else $XDG_CACHE_HOME/dicsynth, else
// $HOME/.cache/dicsynth; "" when none of them is set (nothing is cached on disk then). A relative
// folder is made absolute against the working directory of its first use in the process.
std::string resolveCacheDir(const std::string& option);

}  // namespace dicsynth
