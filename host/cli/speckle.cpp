// PLACEHOLDER during development: replaced by the real subcommand.
#include "cli/commands.h"
#include "core/error.h"
namespace dicsynth::cli {
void addSpeckleCommand(CLI::App& root, RunFn& run) {
  auto* sub = root.add_subcommand("speckle", "(in development)");
  sub->callback([&run] { run = [] () -> int { throw Error("speckle: not implemented yet"); }; });
}
}  // namespace dicsynth::cli
