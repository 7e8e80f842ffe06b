#pragma once
// The options of a render job (render, sweep, compare and the Python module share them): the scene,
// its parameters, frames, sampling, device, and their parsing into the library's types. The
// command line's spelling of them is cli/options.h.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gpu/context.h"
#include "gpu/renderer.h"
#include "model/render_options.h"

namespace dicsynth {

struct RenderArgs {
  std::string scenePath;
  std::vector<std::string> defines;  // "name=value"
  int spp = 4;
  std::uint32_t seed = 1;
  std::string precision = "auto";    // fp32 | df64 | fp64 | auto (render/precision_calibration.h)
  double maxErrorPx = 1e-6;          // auto: largest acceptable geometric error (px)
  std::string device;
  int downscale = 1;
};

// -D name=value list → SceneParams::defines. Throws InputError for a malformed entry.
std::vector<std::pair<std::string, std::string>> parseDefines(const std::vector<std::string>& defines);

// "A:B" (inclusive) or "N" → the list of frames. Throws InputError, also beyond the limits: frame
// numbers up to kMaxFrameNumber (they are Lua integers and file-name numbers), at most
// kMaxFramesPerRun frames in one run (each is evaluated, rendered and written: a million frames is
// days of work; a range past it is a typo, or work for several runs or a sweep).
inline constexpr long long kMaxFrameNumber = 999'999'999;
inline constexpr long long kMaxFramesPerRun = 1'000'000;
std::vector<int> parseFrames(const std::string& text);

// The frames of a job, the reference frame first (a job renders it first: every frame's motion
// truth is measured from it): `reference`, else the first of `frames`.
struct FrameOrder {
  std::vector<int> frames;
  // false: the reference is not among the frames asked for. It is traced for the motion truth (its
  // pixel centres, no samples) and not written, so that a sequence rendered in chunks measures every
  // chunk from one frame (the DIC-developer and docs trials of 2026-11-29: a chunk's flow was
  // relative to its own first frame, or `--frames 1` alone wrote a flow of 0).
  bool referenceWritten = true;
};
FrameOrder referenceFirst(std::vector<int> frames, std::optional<int> reference);

// Validates spp and seed, returns RenderOptions (precision resolved by resolvePrecision).
RenderOptions renderOptions(const RenderArgs& args, int frame);

// The GPU precision: the user's choice, or for "auto" the fastest whose calibrated error on this
// device is ≤ maxErrorPx (calibrating once per device; the choice is reported on stderr).
Precision resolvePrecision(const RenderArgs& args, gpu::Context& context, gpu::Renderer& renderer);

// What resolvePrecision will answer, when that is known without calibrating or failing: the named
// precision, or for "auto" the choice from this device's cached calibration (none when there is no
// valid cache or no precision meets the bound: resolvePrecision then calibrates or says why).
std::optional<Precision> knownPrecision(const RenderArgs& args, gpu::Context& context);

// With validation layers on (DICSYNTH_VALIDATION=1), prints every message they reported to stderr
// and throws Error: a run that the layers flagged must not look successful.
void failOnValidationMessages(const gpu::Context& context);

// True when stderr is a terminal (progress lines are printed only then).
bool stderrIsTerminal();

// A progress callback printing "\r<label> NN%" to stderr when it is a terminal, else null.
std::function<void(double)> progressPrinter(const std::string& label);

}  // namespace dicsynth
