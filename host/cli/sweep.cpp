// `dicsynth sweep SCENE.lua -o DIR`: the options of the sweep runner (sweep/sweep_runner.h).
#include <cstdio>
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
                  "Frame whose pixels the motion ground truth (disp, flow) starts from, in every point (default: "
                  "the first of --frames); a frame not among --frames is traced for it and not written");
  addExrCompressionOption(*sub, cmd->exrCompression);
  addLayersOption(*sub, cmd->layers);
  addStrictFlag(*sub);
  addSweepOptions(*sub, cmd->sweep, "; replaces the scene's `sweep`");
  sub->add_option("--shard", cmd->shard,
                  "I/N: render the points whose index mod N is I (default: from SLURM_ARRAY_TASK_ID/COUNT/MIN)");
  sub->add_flag("--seed-per-point", cmd->seedPerPoint,
                "Point i renders with seed hash(--seed, i) instead of --seed (independent samples per point)");
  sub->add_flag("--merge-only", cmd->mergeOnly, "Only rebuild the manifest from the finished points' records");
  sub->add_flag("--keep-finished", cmd->keepFinished,
                "Refuse (exit 2, before any point) when a finished point was rendered with other inputs, instead of "
                "rendering it again: for resubmitted batch jobs");
  sub->add_flag("--list", cmd->list, "Print the points (index, folder, parameters) and exit");
  sub->callback([cmd, &run] { run = [cmd] {
    const SweepOutcome outcome = runSweep(*cmd);
    // The merge is a sweep's last step (after shards, GNU parallel, a Slurm array): a manifest that
    // lists fewer points than the sweep has is not its result, and exit 0 let a script go on to
    // analyse a partial sweep (the CI trial of 2026-11-29). The manifest is written all the same.
    if (cmd->mergeOnly && outcome.complete < outcome.total) {
      std::fprintf(stderr, "dicsynth: error: sweep --merge-only: %lld of %lld points missing or damaged (the manifest lists the %lld complete; run the sweep again to render the others)\n",
                   outcome.total - outcome.complete, outcome.total, outcome.complete);
      return kExitIncomplete;
    }
    return kExitOk;
  }; });
}

}  // namespace dicsynth::cli
