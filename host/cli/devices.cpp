// PLACEHOLDER during development: replaced by the real subcommand.
#include "cli/commands.h"
#include "core/error.h"
namespace dicsynth::cli {
void addDevicesCommand(CLI::App& root, RunFn& run) {
  auto* sub = root.add_subcommand("devices", "(in development)");
  sub->callback([&run] { run = [] () -> int { throw Error("devices: not implemented yet"); }; });
}
}  // namespace dicsynth::cli
