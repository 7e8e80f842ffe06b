#pragma once
// A sweep as the scene (global `sweep`) or the command line (--sweep) declares it, before its
// points are enumerated (host/sweep/sweep_points.h). Three kinds:
//   Grid:   sweep = { strain = linspace(0, 0.01, 11), noise = {0, 1, 2} }  every combination
//   Points: sweep = points { {strain = 0, noise = 1}, {strain = 0.01, noise = 0} }  as listed
//   Random: sweep = random { n = 1000, seed = 7, strain = {0, 0.01} }  uniform in [lo, hi)
// The scene functions linspace, points and random are registered by registerSweepFunctions
// (sweep_functions.cpp, which documents them).
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

struct lua_State;

namespace dicsynth {

// One value of a sweep parameter: a number, a boolean or a string, set as a Lua global.
// Largest number of points of one declaration (scene or --sweep/--random): points are generated on
// demand, but each value a declaration lists is held (~90 bytes: a one-parameter sweep of listed
// values at this limit takes 0.9 GB; SweepAxis), so 10 million is far beyond any sweep a machine
// renders, and far below a mistake like n = 1e12 that would exhaust memory instead of failing clearly.
inline constexpr std::int64_t kMaxSweepPoints = 10'000'000;

// The i-th of n values evenly spaced from a to b (n >= 1): linspace(a, b, n) in a scene and
// --sweep NAME=A:B:N both use it, so the two spell the same points. The last value is b itself
// (a + (n-1)·(b-a)/(n-1) may round off b by an ulp); n = 1 gives a. Where b − a overflows (a and
// b near ±1.8e308 with opposite signs), (1 − t)·a + t·b, which does not, gives the same points.
inline double linspaceValue(double a, double b, std::int64_t n, std::int64_t i) {
  if (n == 1) return a;
  if (i == n - 1) return b;
  const double span = b - a;
  if (std::isfinite(span)) return a + double(i) * span / double(n - 1);
  const double t = double(i) / double(n - 1);
  return (1 - t) * a + t * b;
}

struct SweepValue {
  enum class Kind { Number, Boolean, String };
  Kind kind = Kind::Number;
  double number = 0;
  bool boolean = false;
  std::string text;

  static SweepValue ofNumber(double v) { return {Kind::Number, v, false, {}}; }
  // The text a -D define would carry to give the scene this value (numbers exact, shortest).
  std::string defineText() const;
  std::string json() const;  // 0.01, true, "abc"
  bool operator==(const SweepValue&) const = default;
};

using SweepAssignment = std::vector<std::pair<std::string, SweepValue>>;  // sorted by name

// One parameter of a grid: its listed values, or (spaced > 0) the `spaced` values evenly spaced from
// a to b of --sweep NAME=A:B:N, made on demand: a listed value is held (~90 bytes), so a
// one-parameter sweep of 10 million listed values takes ~0.9 GB, of 10 million spaced ones nothing.
// A scene's linspace() is a Lua table of listed values (the scene may read it as one).
struct SweepAxis {
  std::string name;
  std::vector<SweepValue> values;
  double a = 0, b = 0;
  std::int64_t spaced = 0;
  std::int64_t size() const { return spaced > 0 ? spaced : std::int64_t(values.size()); }
  SweepValue at(std::int64_t i) const {
    return spaced > 0 ? SweepValue::ofNumber(linspaceValue(a, b, spaced, i)) : values[std::size_t(i)];
  }
};

struct SweepRange {
  std::string name;
  double lo = 0, hi = 0;  // uniform in [lo, hi)
};

struct SweepDeclaration {
  enum class Kind { None, Grid, Points, Random };
  Kind kind = Kind::None;
  std::string origin;  // "SCENE:LINE" or "--sweep", for messages
  std::vector<SweepAxis> grid;                                       // Grid: sorted by name
  std::vector<SweepAssignment> points;                               // Points: each sorted by name
  std::vector<SweepRange> ranges;                                    // Random: sorted by name
  std::int64_t count = 0;                                            // Random: n
  std::uint32_t seed = 1;                                            // Random: seed
};

// Runs the scene once with `params` (the sweep's parameters unset: the scene's defaults apply)
// and returns its global `sweep` (Kind::None when the scene has none). Throws InputError
// ("SCENE:LINE: ...") for a malformed declaration or any scene error.
SweepDeclaration loadSweepDeclaration(const std::string& path, const SceneParams& params);

namespace scene {
// loadScene, calling `inspect` on the Lua state after the chunk ran (defines checked).
Scene loadSceneInspecting(const std::string& path, const SceneParams& params,
                          const std::function<void(lua_State*)>& inspect);
// Reads the global `sweep` of a state whose scene has run (sweep_functions.cpp). A table is read
// after the run, so its errors name the line that first assigned `sweep`, which _G's __newindex
// (lua_scene.cpp) keeps in the registry under kSweepLineKey.
inline constexpr const char* kSweepLineKey = "dicsynth.sweepLine";
SweepDeclaration readSweepGlobal(lua_State* L);
}  // namespace scene

}  // namespace dicsynth
