#pragma once
// Options shared by the subcommands that render a scene (render, sweep, compare), as the command
// line spells them (CLI11); their values and parsing are job/render_args.h.
#include <CLI/CLI.hpp>

#include <string>

#include "job/render_args.h"
#include "sweep/sweep_points.h"

namespace dicsynth::cli {

void addRenderArgs(CLI::App& app, RenderArgs& args);

// --exr-compression: how the ground-truth EXR is compressed (render, sweep).
void addExrCompressionOption(CLI::App& app, std::string& compression);

// --frames A:B or N (render, sweep; parsed by job/render_args.h's parseFrames). Given empty it is
// refused here: an empty value would read as "not given" and render one unnumbered frame.
void addFramesOption(CLI::App& app, std::string& frames, const std::string& help);

// --layers: which outputs are computed and written (render, sweep; model/layers.h).
void addLayersOption(CLI::App& app, std::string& layers);

// --strict (render, sweep): a run that said a warning ends with exit 4 once its work is done, so
// that an unattended job cannot pass with, e.g., a camera that saw nothing. main() judges it.
void addStrictFlag(CLI::App& app);
bool strictWarnings();
// A run that writes no file (render --check): --strict's message then says so (it said "its files
// are written": the review of 2026-11-29).
void markNothingWritten();
bool nothingWritten();

// --sweep, --random, --random-seed (sweep/sweep_points.h). `effect` ends the --sweep help text: what
// the subcommand does with the points.
void addSweepOptions(CLI::App& app, SweepOptions& options, const std::string& effect);

}  // namespace dicsynth::cli
