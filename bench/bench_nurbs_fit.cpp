// Cost of Nurbs.deform (issue 16), measured in one run on one machine; prints markdown rows for
// bench/RESULTS.md ("Nurbs.deform fit cost").
//
//   build/bench_nurbs_fit [--repeat 3]
//
// For the example scenes with a deformation (a Lua field: sinusoid_plate, stereo_sinusoid; an FE
// field read with VTK: plate_hole) at several tolerances: the time of loading frame 1's scene
// (evaluation + fit; the median of --repeat loads, each with a tolerance no earlier load used, so
// that the fit memory does not answer), the error reached, the control points and refinements;
// then the time of loading frame 2 right after frame 1 (the fit memory verifying and reusing it).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_args.h"
#include "scene/scene.h"

using namespace dicsynth;

namespace {

double seconds(auto&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const Deformation& deformationOf(const Scene& scene) {
  for (const Object& o : scene.objects)
    if (o.shape.deformation) return *o.shape.deformation;
  std::fprintf(stderr, "bench_nurbs_fit: the scene has no Nurbs.deform surface\n");
  std::exit(1);
}

}  // namespace

static int run(int argc, char** argv) {
  int repeat = 3;  // --repeat R, its only option
  for (int i = 1; i < argc; i += 2) {
    if (std::strcmp(argv[i], "--repeat") != 0) throw InputError(std::string("unknown option ") + argv[i]);
    if (i + 1 >= argc) throw InputError("--repeat needs a value");
    repeat = bench::positiveCount("--repeat", argv[i + 1]);
  }
  std::printf("| scene (field) | tolerance | fit error | control points | refinements | frame 1: load + fit | frame 2: reuse |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  struct Case {
    const char* scene;
    const char* field;
    std::vector<double> tolerances;
  };
  const std::vector<Case> cases = {
      {"sinusoid_plate", "Lua", {1e-7, 1e-8, 1e-9, 1e-10}},
      {"stereo_sinusoid", "Lua", {1e-8, 1e-9, 1e-10}},
      {"plate_hole", "FE mesh, VTK", {1e-7, 5e-8, 2e-8, 1e-8}},
  };
  for (const Case& c : cases)
    for (double tolerance : c.tolerances) {
      const std::string path = std::string(DS_SOURCE_DIR) + "/scenes/" + c.scene + ".lua";
      std::vector<double> times;
      NurbsFitReport report;
      double reuse = 0;
      for (int r = 0; r < repeat; ++r) {
        // A tolerance nudged by a relative 1e-12 per repetition: a different key for the memory.
        char text[64];
        std::snprintf(text, sizeof text, "%.17g", tolerance * (1 + 1e-12 * r));
        SceneParams params;
        params.defines = {{"tolerance", text}};
        params.frame = 1;
        Scene scene;
        times.push_back(seconds([&] { scene = loadScene(path, params); }));
        report = deformationOf(scene).report;
        if (r == 0) {
          params.frame = 2;
          reuse = seconds([&] { scene = loadScene(path, params); });
          if (!deformationOf(scene).fromCache) std::fprintf(stderr, "bench_nurbs_fit: frame 2 was refitted\n");
        }
      }
      std::sort(times.begin(), times.end());
      std::printf("| %s (%s) | %.0e m | %.2g m | %zu | %d | %.2f s | %.2f s |\n", c.scene, c.field, tolerance,
                  report.maxError_m, report.controlPoints, report.refinements, times[times.size() / 2], reuse);
      std::fflush(stdout);
    }
  return 0;
}

int main(int argc, char** argv) {
  return dicsynth::bench::guarded([&] { return run(argc, argv); });
}
