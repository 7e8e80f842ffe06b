#include "cli/options.h"

#include <algorithm>
#include <string>
#include <vector>

#include "io/outputs.h"
#include "model/layers.h"
#include "model/render_options.h"

namespace dicsynth::cli {

void decimalIntegers(CLI::App& app) {
  // An empty description leaves the help's type names ("INT") as they are.
  const CLI::Validator decimal(
      [](std::string& text) -> std::string {
        const std::size_t digits = text.find_first_not_of("+-") == 1 ? 1 : 0;
        if (text.size() <= digits || text.find_first_not_of("0123456789", digits) != std::string::npos)
          return "expected a decimal integer, not '" + text + "'";
        const std::size_t first = std::min(text.find_first_not_of('0', digits), text.size() - 1);
        text = text.substr(0, digits) + text.substr(first);
        return "";
      },
      "", "decimal integer");
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) option->transform(decimal);
  }
  for (CLI::App* sub : app.get_subcommands({})) decimalIntegers(*sub);
}

void addSweepOptions(CLI::App& app, SweepOptions& options, const std::string& effect) {
  app.add_option("--sweep", options.sweeps,
                 "NAME=A:B:N (N values from A to B), NAME=V1,V2,... or, with --random, NAME=LO:HI" + effect);
  CLI::Option* random = app.add_option("--random", options.randomCount, "Random sweep of N points over the --sweep ranges");
  // Without --random it would be ignored silently.
  app.add_option("--random-seed", options.randomSeed, "Seed of --random")->capture_default_str()->needs(random);
}

void addExrCompressionOption(CLI::App& app, std::string& compression) {
  app.add_option("--exr-compression", compression,
                 "Lossless compression of the ground-truth EXR: zip (smallest of the fast ones), zips, piz, "
                 "rle (2.3x larger than zip for Figure 1, 8.7x for a speckle scene's smooth layers; nearly free to "
                 "write: for large sweeps on few cores), none")
      ->check(CLI::IsMember(kExrCompressions))
      ->capture_default_str();
}

void addFramesOption(CLI::App& app, std::string& frames, const std::string& help) {
  app.add_option("--frames", frames, help)
      ->check(CLI::Validator(
          [](const std::string& v) { return v.empty() ? std::string("expected A:B or N, got nothing") : std::string(); }, ""));
}

namespace {
bool strict = false;  // set by --strict of the one subcommand that runs
}  // namespace

void addStrictFlag(CLI::App& app) {
  app.add_flag("--strict", strict,
               "Warnings fail the run: exit 4 once its work is done (the files are written), for unattended jobs");
}

bool strictWarnings() { return strict; }

namespace {
bool writesNothing = false;
}  // namespace

void markNothingWritten() { writesNothing = true; }
bool nothingWritten() { return writesNothing; }

void addLayersOption(CLI::App& app, std::string& layers) {
  // The names from the layer schema (model/layers.h), so the help cannot miss one.
  std::string names;
  for (const LayerSpec& spec : layerSpecs())
    names += std::string(names.empty() ? "" : ", ") + spec.name + (spec.layer == Layer::Image ? " (the TIFF)" : "");
  app.add_option("--layers", layers,
                 "Outputs to compute and write: all (every layer the scene can produce), or a comma-separated "
                 "list of " + names + " (EXR channel groups but image; no EXR without one)")
      ->capture_default_str();
}

namespace {

// --precision's values: every precision's name, then auto.
std::vector<std::string> precisionChoices() {
  std::vector<std::string> names;
  for (Precision p : kPrecisions) names.push_back(toString(p));
  names.push_back("auto");
  return names;
}

}  // namespace

void addRenderArgs(CLI::App& app, RenderArgs& args) {
  app.add_option("scene", args.scenePath, "Scene file (Lua)")->required();
  app.add_option("-D,--define", args.defines,
                 "Set a scene global before the scene runs: name=value (number, true/false, or string)");
  app.add_option("--spp", args.spp, "Samples per pixel, stratified over the sensitive area")
      ->capture_default_str();
  app.add_option("--seed", args.seed, "Seed of the sample positions")->capture_default_str();
  app.add_option("--precision", args.precision,
                 "GPU arithmetic: fp32, df64 (float pairs), fp64, or auto: the fastest whose measured geometric "
                 "error on this device is <= --max-error-px")
      ->check(CLI::IsMember(precisionChoices()))
      ->capture_default_str();
  // Checked by renderOptions (a finite number > 0), with the message the manual shows for every bad value.
  app.add_option("--max-error-px", args.maxErrorPx, "--precision auto: largest acceptable geometric error (px)")
      ->capture_default_str();
  app.add_option("--device", args.device, "Vulkan device: index, or a substring of its name or else of its driver (see `dicsynth devices`)");
  app.add_option("--downscale", args.downscale,
                 "Divide every camera's resolution by this integer, keeping the field of view")
      ->capture_default_str();
}

}  // namespace dicsynth::cli
