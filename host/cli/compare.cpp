// `dicsynth compare SCENE.lua`: renders on the CPU reference and on the GPU with the same samples,
// prints the differences per camera and exits 1 when one exceeds the precision's tolerance.
#include <cstdio>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/render_args.h"
#include "core/json.h"
#include "cpu/reference_renderer.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "render/compare.h"

namespace dicsynth::cli {
namespace {

struct CompareCommand {
  RenderArgs args;
  int frame = 0;
  bool json = false;
};

std::string toJson(const std::string& scene, const RenderResult& cpu, const RenderResult& gpu, int spp,
                   const Tolerances& t, const std::vector<CameraDifference>& diffs, bool pass) {
  using namespace json;
  std::ostringstream o;
  o << "{\"scene\": " << quote(scene) << ", \"precision\": " << quote(gpu.precision)
    << ", \"device\": " << quote(gpu.device) << ", \"spp\": " << spp
    << ", \"cpu_seconds\": " << number(cpu.renderSeconds) << ", \"gpu_seconds\": " << number(gpu.renderSeconds)
    << ", \"tolerances\": {\"radiance\": " << number(t.radiance) << ", \"position_m\": " << number(t.position_m)
    << ", \"uv\": " << number(t.uv) << ", \"epsilon\": " << number(t.epsilon) << ", \"k\": " << number(t.k)
    << ", \"outlier_fraction\": " << number(t.outlierFraction) << "}, \"cameras\": {";
  for (std::size_t i = 0; i < diffs.size(); ++i) {
    const CameraDifference& d = diffs[i];
    o << (i ? ", " : "") << quote(d.camera) << ": {\"pixels\": " << d.pixels
      << ", \"max_radiance_diff\": " << number(d.maxRadianceDiff)
      << ", \"rms_radiance_diff\": " << number(d.rmsRadianceDiff) << ", \"pixels_differing\": " << d.pixelsDiffering
      << ", \"radiance_outliers\": " << d.radianceOutliers << ", \"radiance_outliers_off_edge\": "
      << d.radianceOutliersOffEdge << ", \"object_id_mismatches\": " << d.objectIdMismatches
      << ", \"object_id_mismatches_off_edge\": " << d.objectIdMismatchesOffEdge
      << ", \"max_uv_diff\": " << number(d.maxUvDiff) << ", \"max_P_diff_m\": " << number(d.maxPositionDiff_m)
      << ", \"max_Z_diff_m\": " << number(d.maxDepthDiff_m) << ", \"max_geometry_ratio\": " << number(d.maxGeometryRatio)
      << ", \"geometry_outliers\": " << d.geometryOutliers
      << ", \"pass\": " << boolean(withinTolerance(d, t)) << "}";
  }
  o << "}, \"pass\": " << boolean(pass) << "}";
  return o.str();
}

int runCompare(const CompareCommand& cmd) {
  RenderOptions options = renderOptions(cmd.args, cmd.frame);
  const Scene scene = loadScene(cmd.args.scenePath, {parseDefines(cmd.args.defines), cmd.frame});
  const PreparedScene prepared = prepareScene(scene, {cmd.args.downscale});
  gpu::ContextOptions co;
  co.device = cmd.args.device;
  gpu::Context context(co);
  gpu::Renderer renderer(context);
  options.precision = resolvePrecision(cmd.args, context, renderer);

  options.progress = progressPrinter("cpu reference");
  const RenderResult cpu = cpu::render(prepared, options);
  options.progress = progressPrinter("gpu " + std::string(toString(options.precision)));
  const RenderResult gpu = renderer.render(prepared, options);

  failOnValidationMessages(context);
  const Tolerances tol = tolerancesFor(options.precision);
  const auto diffs = compareResults(prepared, cpu, gpu, tol);
  bool pass = true;
  for (const auto& d : diffs) pass &= withinTolerance(d, tol);
  if (cmd.json) {
    std::printf("%s\n", toJson(cmd.args.scenePath, cpu, gpu, options.samplesPerPixel, tol, diffs, pass).c_str());
  } else {
    std::printf("%s: cpu %.2f s, gpu %s on %s %.2f s, %d spp\n", cmd.args.scenePath.c_str(), cpu.renderSeconds,
                gpu.precision.c_str(), gpu.device.c_str(), gpu.renderSeconds, options.samplesPerPixel);
    for (const auto& d : diffs) {
      std::printf(
          "  %s: %s\n    radiance (fraction of full scale): max %.3g, rms %.3g, over tolerance %.3g: %zu px (%zu off edges);"
          " digital numbers differ: %zu px\n    pixel-centre rays: different object %zu px (%zu off edges); max |duv| %.3g,"
          " max |dP| %.3g m, max |dZ| %.3g m; worst error/bound %.3g, over bound: %zu px\n",
          d.camera.c_str(), withinTolerance(d, tol) ? "PASS" : "FAIL", d.maxRadianceDiff, d.rmsRadianceDiff,
          tol.radiance, d.radianceOutliers, d.radianceOutliersOffEdge, d.pixelsDiffering, d.objectIdMismatches,
          d.objectIdMismatchesOffEdge, d.maxUvDiff,
          d.maxPositionDiff_m, d.maxDepthDiff_m, d.maxGeometryRatio, d.geometryOutliers);
    }
    if (tol.epsilon > 0)
      std::printf("tolerances (%s): radiance %.3g; P and uv per pixel, %g eps D / max(cos, sqrt eps) (README);"
                  " outliers off edges <= %.3g of the pixels\n",
                  gpu.precision.c_str(), tol.radiance, tol.k, tol.outlierFraction);
    else
      std::printf("tolerances (%s): radiance %.3g, P %.3g m, uv %.3g, no outliers\n", gpu.precision.c_str(),
                  tol.radiance, tol.position_m, tol.uv);
  }
  return pass ? kExitOk : kExitCompareFailed;
}

}  // namespace

void addCompareCommand(CLI::App& root, RunFn& run) {
  auto cmd = std::make_shared<CompareCommand>();
  CLI::App* sub = root.add_subcommand(
      "compare", "Render on the CPU reference and the GPU with the same samples and compare (exit 1 if over tolerance)");
  addRenderArgs(*sub, cmd->args);
  sub->add_option("--frame", cmd->frame, "Value of the scene global `frame`")->capture_default_str();
  sub->add_flag("--json", cmd->json, "Print one JSON object instead of text");
  sub->callback([cmd, &run] { run = [cmd] { return runCompare(*cmd); }; });
}

}  // namespace dicsynth::cli
