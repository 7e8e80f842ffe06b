// `dicsynth bench`: the run-time-versus-error benchmark (job/benchmark.h) over three scenes at
// 1600 × 1200: the paper's Figure 1 (sphere), a NURBS plate under 0.2 % strain, the necking
// dogbone. Writes DIR/bench.csv and DIR/bench.svg (atomically) and prints a table, or with --json
// the rows as a JSON array.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "job/benchmark.h"
#include "job/render_job.h"

namespace dicsynth::cli {
namespace {

struct BenchCommand {
  std::string outputDir = "bench-out";
  std::string scenesDir = std::string(DS_SOURCE_DIR) + "/scenes";
  bool json = false;
  BenchmarkOptions options;
};

int runBench(BenchCommand cmd) {
  if (cmd.options.runs < 1 || cmd.options.cpuRuns < 1) throw InputError("--runs and --cpu-runs must be >= 1");
  if (cmd.options.samplesPerPixel < 1) throw InputError("--spp must be >= 1");
  // Checked before the first scene renders (an audit found stride 0 failing an internal check
  // after the first render, exit 3).
  if (cmd.options.errorStride < 1)
    throw InputError("--error-stride " + std::to_string(cmd.options.errorStride) + ": must be >= 1 (pixels)");
  if (cmd.options.downscale < 1)
    throw InputError("--downscale " + std::to_string(cmd.options.downscale) + ": must be >= 1");
  cmd.options.scenes = {{"figure1", cmd.scenesDir + "/figure1.lua", {}},
                        {"nurbs_plate", cmd.scenesDir + "/nurbs_plate.lua", {{"strain", "0.002"}}},
                        {"dogbone", cmd.scenesDir + "/dogbone.lua", {{"necking", "0.002"}}}};
  for (const auto& s : cmd.options.scenes)
    if (!std::filesystem::exists(s.path)) throw InputError("--scenes " + cmd.scenesDir + ": no " + s.path);
  // Before the benchmark, as `render` does: a folder that cannot take the files was found after
  // minutes of work (the faults audit of 2026-11-28).
  const std::string csv = cmd.outputDir + "/bench.csv", svg = cmd.outputDir + "/bench.svg";
  checkOutputWritable(cmd.outputDir);
  for (const std::string& file : {csv, svg})
    if (const std::string why = notAFileTarget(file); !why.empty())
      throw InputError("-o " + cmd.outputDir + ": " + file + " " + why + ", which the benchmark's file would replace");
  cmd.options.log = [](const std::string& line) { std::fprintf(stderr, "bench: %s\n", line.c_str()); };

  const std::vector<BenchmarkRow> rows = runBenchmark(cmd.options);
  // The two files together or neither (a full disk left bench.csv and the folder made for it), and
  // the folder made for them removed again when they fail.
  // With the folders above it that it made (-o new/a/b left new/a behind).
  const std::filesystem::path existing = nearestExistingFolder(cmd.outputDir);
  createOutputDir(cmd.outputDir);
  try {
    AtomicFile csvFile(csv), svgFile(svg);
    writeText(csvFile, benchmarkCsv(rows));
    writeText(svgFile, benchmarkSvg(rows));
    csvFile.commit();
    svgFile.commit();
  } catch (...) {
    removeCreatedFolders(cmd.outputDir, existing);  // the AtomicFiles removed their temporaries
    throw;
  }
  if (cmd.json) {
    std::printf("%s", benchmarkJson(rows).c_str());
  } else {
    std::printf("%-12s %-4s %-5s %9s %9s %11s %11s %11s %6s\n", "scene", "", "prec.", "s/frame", "Mrays/s",
                "geom max px", "geom rms px", "DN12 max", "wrong");
    for (const BenchmarkRow& r : rows)
      std::printf("%-12s %-4s %-5s %9.3f %9.2f %11.3g %11.3g %11.3g %6zu\n", r.scene.c_str(), r.backend.c_str(),
                  r.precision.c_str(), r.secondsPerFrame, r.mraysPerSecond, r.geomErrPxMax, r.geomErrPxRms,
                  r.radianceErrDnMax, r.wrongHits);
    std::printf("wrote %s and %s\n", csv.c_str(), svg.c_str());
  }
  return kExitOk;
}

}  // namespace

void addBenchCommand(CLI::App& root, RunFn& run) {
  auto cmd = std::make_shared<BenchCommand>();
  CLI::App* sub = root.add_subcommand(
      "bench", "Run time versus error: CPU reference and every GPU precision on three scenes (CSV + SVG plot)");
  sub->add_option("-o,--output,--out", cmd->outputDir, "Output folder for bench.csv and bench.svg")->capture_default_str();
  sub->add_option("--scenes", cmd->scenesDir, "Folder holding figure1.lua, nurbs_plate.lua, dogbone.lua")
      ->capture_default_str();
  sub->add_flag("--json", cmd->json, "Print the rows as a JSON array instead of a table");
  sub->add_option("--runs", cmd->options.runs, "GPU runs per precision (median reported)")->capture_default_str();
  sub->add_option("--cpu-runs", cmd->options.cpuRuns, "CPU reference runs (median reported)")->capture_default_str();
  sub->add_option("--spp", cmd->options.samplesPerPixel, "Samples per pixel")->capture_default_str();
  sub->add_option("--downscale", cmd->options.downscale, "Divide the scenes' resolution (quick runs)")
      ->capture_default_str();
  sub->add_option("--error-stride", cmd->options.errorStride,
                  "Material-point error on every n-th pixel in x and y (2 reference rays each)")
      ->capture_default_str();
  sub->add_option("--device", cmd->options.device, "Vulkan device: index, or a substring of its name or else of its driver");
  sub->callback([cmd, &run] { run = [cmd] { return runBench(*cmd); }; });
}

}  // namespace dicsynth::cli
