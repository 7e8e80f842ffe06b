// `dicsynth sweep SCENE.lua -o DIR`: the options of the sweep runner (sweep/sweep_runner.h).
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "sweep/sweep_runner.h"

namespace dicsynth::cli {

void addSweepCommand(CLI::App& root, RunFn& run) {
  auto cmd = std::make_shared<SweepRun>();
  CLI::App* sub = root.add_subcommand(
      "sweep", "Render every point of a parameter sweep into DIR/point_NNNNN/, with DIR/manifest.csv and .json");
  addRenderArgs(*sub, cmd->args);
  sub->add_option("-o,--output", cmd->outputDir, "Output folder of the sweep (created if missing)")->required();
  sub->add_option("--backend", cmd->backend, "gpu (Vulkan) or cpu (double-precision reference)")
      ->check(CLI::IsMember({"gpu", "cpu"}))
      ->capture_default_str();
  addFramesOption(*sub, cmd->frames, "Frames A:B or N of every point (as render --frames)");
  sub->add_option("--reference-frame", cmd->referenceFrame,
                  "Frame whose pixels the motion ground truth (disp, flow) starts from, in every point; one of "
                  "--frames (default: the first)");
  addExrCompressionOption(*sub, cmd->exrCompression);
  addLayersOption(*sub, cmd->layers);
  addStrictFlag(*sub);
  addSweepOptions(*sub, cmd->sweep, "; replaces the scene's `sweep`");
  sub->add_option("--shard", cmd->shard,
                  "I/N: render the points whose index mod N is I (default: from SLURM_ARRAY_TASK_ID/COUNT/MIN)");
  sub->add_flag("--seed-per-point", cmd->seedPerPoint,
                "Point i renders with seed hash(--seed, i) instead of --seed (independent samples per point)");
  sub->add_flag("--merge-only", cmd->mergeOnly, "Only rebuild the manifest from the finished points' records");
  sub->add_flag("--list", cmd->list, "Print the points (index, folder, parameters) and exit");
  sub->callback([cmd, &run] { run = [cmd] {
    runSweep(*cmd);
    return kExitOk;
  }; });
}

}  // namespace dicsynth::cli
