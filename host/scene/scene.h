#pragma once
// Loading a scene: a sandboxed Lua 5.4 state runs the scene file (host/scene/lua_scene.cpp) and
// returns the Scene of model/scene.h. The values set before it runs, its limits, and the names the
// scene language reserves.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "model/scene.h"

namespace dicsynth {

// Values set as Lua globals before the scene runs.
struct SceneParams {
  std::vector<std::pair<std::string, std::string>> defines;  // -D name=value (number/bool/string)
  int frame = 0;                                              // global `frame`
  // Names among `defines` set by a sweep point (dicsynth sweep): messages call them sweep
  // parameters instead of -D options.
  std::vector<std::string> sweepParameters;
  // Limits of the scene's Lua code. A real scene runs in milliseconds and needs a few MiB; the
  // limits only turn a runaway scene (endless loop, table growing without end) into a clear
  // "FILE:LINE: scene exceeded the ... limit" error instead of a hang or an exhausted machine.
  // Instructions: Lua VM instructions; this machine runs ~200 M/s, so the default stops a
  // runaway loop within about half a second, yet leaves ~20x the headroom that a scene building
  // 100 000 triangles in a loop (~5 M instructions) needs.
  std::uint64_t maxInstructions = 100'000'000;
  // Memory: bytes of the Lua heap. A scene value is under 1 KiB, so 256 MiB holds well over
  // 100 000 objects; far beyond what the renderers take, far below the machine's memory.
  std::size_t maxMemoryBytes = std::size_t{256} << 20;
  // Wall-clock time of the evaluation (seconds). Real scenes take milliseconds, Nurbs.deform fits
  // up to a few seconds (bench/RESULTS.md); a minute stops a runaway scene whose loop of long
  // calls the instruction limit cannot see. 0: the environment's DICSYNTH_SCENE_SECONDS, else 60.
  double maxSeconds = 0;
  // The scene's print and constructors' reports (Nurbs.deform's fit) write nothing: set when a
  // scene is evaluated again after a first evaluation whose output the user saw (render, sweep).
  bool quiet = false;
  // A define the scene never reads is a typo: refused (InputError) when true. A run of several frames
  // sets false, since a scene may read a define only in some frames (`frame >= 1 and ...`), and
  // refuses one that no frame reads (UnreadDefines).
  bool requireDefinesRead = true;
};

// The longest camera name (with a rig's ".left"/".right"): names become output file names.
inline constexpr std::size_t kMaxCameraNameBytes = 128;

// The largest scene file loadScene reads (docs/limits.md).
inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t(16) << 20;

// Whether `name` is taken by the scene language (a constructor table, a function, a Lua library,
// a keyword, `frame`): a -D option or a sweep parameter cannot use it.
bool isSceneLanguageName(const std::string& name);

// Loads and validates a scene. Throws InputError("file:line: message") on any error.
Scene loadScene(const std::string& path, const SceneParams& params);

// The defines that none of a run's frames read, gathered frame by frame (scenes loaded with
// requireDefinesRead = false); check() refuses the first of them as loadScene would.
class UnreadDefines {
 public:
  void add(const Scene& scene);
  void check(const std::string& scenePath, const std::vector<std::string>& sweepParameters) const;

 private:
  bool any_ = false;                // a scene was added
  std::vector<std::string> unread_;  // unread by every scene added, in the order given
  std::vector<std::string> unsetRead_;  // globals any scene added read unset (Scene::unsetGlobalsRead)
};

}  // namespace dicsynth
