// PLACEHOLDER during development: replaced by the real subcommand.
#include "cli/commands.h"
#include "core/error.h"
namespace dicsynth::cli {
void addRenderCommand(CLI::App& root, RunFn& run) {
  auto* sub = root.add_subcommand("render", "(in development)");
  sub->callback([&run] { run = [] () -> int { throw Error("render: not implemented yet"); }; });
}
}  // namespace dicsynth::cli
