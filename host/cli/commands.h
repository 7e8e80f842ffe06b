#pragma once
// One subcommand per file (render.cpp, compare.cpp, devices.cpp, speckle.cpp, bench.cpp, sweep.cpp, preview.cpp). Each add*Command
// registers its CLI11 subcommand and, when that subcommand is parsed, stores in `run` the function
// that does the work and returns the process exit code.
#include <CLI/CLI.hpp>

#include <functional>

namespace dicsynth::cli {

// Exit codes, documented in docs/commands.md.
inline constexpr int kExitOk = 0;
inline constexpr int kExitCompareFailed = 1;  // compare: a difference exceeds its tolerance
inline constexpr int kExitIncomplete = 1;     // sweep --merge-only: points missing (a check that found a gap, as compare's)
inline constexpr int kExitBadInput = 2;       // scene/parameter/file errors (InputError, CLI errors)
inline constexpr int kExitFailure = 3;        // Vulkan, I/O or internal failure (Error)
inline constexpr int kExitStrictWarnings = 4;  // --strict: the run finished, with warnings

using RunFn = std::function<int()>;

void addRenderCommand(CLI::App& root, RunFn& run);
void addCompareCommand(CLI::App& root, RunFn& run);
void addDevicesCommand(CLI::App& root, RunFn& run);
void addSpeckleCommand(CLI::App& root, RunFn& run);
void addBenchCommand(CLI::App& root, RunFn& run);
void addSweepCommand(CLI::App& root, RunFn& run);
void addPreviewCommand(CLI::App& root, RunFn& run);

}  // namespace dicsynth::cli
