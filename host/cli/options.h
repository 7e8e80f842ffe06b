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

// Every integer option of `app` and its subcommands reads decimal digits only, with an optional sign:
// CLI11 reads integers with strtoll's base 0, so `--reference-frame 0010` was frame 8 (octal),
// `0x10` 16 and " 3" 3, while `--frames 0010` and `-D v=010` are decimal 10 (the hostile-input
// trial of 2026-11-29; file names have 4-digit frame numbers, which invite the leading zeros).
// Leading zeros are dropped; anything else is refused with the option's name. Call once every
// option is added.
void decimalIntegers(CLI::App& app);

// --sweep, --random, --random-seed (sweep/sweep_points.h). `effect` ends the --sweep help text: what
// the subcommand does with the points.
void addSweepOptions(CLI::App& app, SweepOptions& options, const std::string& effect);

}  // namespace dicsynth::cli
