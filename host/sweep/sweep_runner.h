#pragma once
// The sweep runner (`dicsynth sweep`, docs/sweeps.md): renders every point of a sweep into
// DIR/point_NNNNN/ with the files `render` writes, records each finished point (point_record.h)
// and rebuilds DIR/manifest.{csv,json} (manifest.h). One process keeps the device, the pipelines
// and the resolved precision across its points (RenderSession). Points already complete are
// skipped; a shard (--shard I/N, or a Slurm job array) renders the points with index ≡ I (mod N).
#include <optional>
#include <string>

#include "job/render_args.h"
#include "sweep/sweep_points.h"

namespace dicsynth {

// What a sweep run is asked (cli/sweep.cpp spells it as options).
struct SweepRun {
  RenderArgs args;
  std::string outputDir;
  std::string backend = "gpu";
  std::string frames;          // "" (one unnumbered frame), "A:B" or "N" (job/render_args.h parseFrames)
  std::optional<int> referenceFrame;  // the frame motion truth starts from; default: the first of frames
  SweepOptions sweep;          // replaces the scene's `sweep` when it names any
  std::string shard;           // "I/N"; "" for the Slurm job array's task, else the whole sweep
  std::string exrCompression = "zip";
  std::string layers = "all";
  bool seedPerPoint = false;   // point i renders with seed hash(seed, i)
  bool mergeOnly = false;      // only rebuild the manifest from the finished points' records
  bool keepFinished = false;   // a finished point of other inputs stops the run before any point
  bool list = false;           // print the points (index, folder, parameters) and render nothing
};

// How many of the sweep's points the manifest lists as complete, of how many (0 of 0 for --list).
struct SweepOutcome {
  long long complete = 0;
  long long total = 0;
};

// Runs it, printing a summary line (or the list) on stdout and progress on stderr. Throws
// InputError for bad input (before any point renders), Error for a failure.
SweepOutcome runSweep(const SweepRun& run);

}  // namespace dicsynth
