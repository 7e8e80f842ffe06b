#include "cli/suggestion.h"

#include <algorithm>
#include <vector>

#include "core/closest_name.h"

namespace dicsynth::cli {

std::string suggestion(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return "";
  const std::string first = argv[1];
  std::vector<std::string> commands;
  CLI::App* command = nullptr;
  for (CLI::App* sub : app.get_subcommands({})) {
    commands.push_back(sub->get_name());
    if (sub->get_name() == first) command = sub;
  }
  if (!command) {
    if (first.empty() || first[0] == '-') return "";
    std::string list;
    for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
    const auto best = closestName(first, commands);
    return best ? " (did you mean '" + *best + "'? The commands: " + list + ")"
                : " ('" + first + "' is no command; the commands: " + list + ")";
  }
  // The first --option of the command line that the command lacks (--name or --name=value).
  std::vector<std::string> options;
  for (const CLI::Option* option : command->get_options())
    for (const std::string& name : option->get_lnames()) options.push_back("--" + name);
  for (int i = 2; i < argc; ++i) {
    std::string word = argv[i];
    if (word.rfind("--", 0) != 0 || word.size() == 2) continue;
    word = word.substr(0, word.find('='));
    if (std::find(options.begin(), options.end(), word) != options.end()) continue;
    if (const auto best = closestName(word, options)) return " (did you mean " + *best + " for " + word + "?)";
    return "";
  }
  return "";
}

}  // namespace dicsynth::cli
