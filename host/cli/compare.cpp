// PLACEHOLDER during development: replaced by the real subcommand.
#include "cli/commands.h"
#include "core/error.h"
namespace dicsynth::cli {
void addCompareCommand(CLI::App& root, RunFn& run) {
  auto* sub = root.add_subcommand("compare", "(in development)");
  sub->callback([&run] { run = [] () -> int { throw Error("compare: not implemented yet"); }; });
}
}  // namespace dicsynth::cli
