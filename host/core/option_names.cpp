#include "core/option_names.h"

#include <atomic>

namespace dicsynth {

namespace {
std::atomic<OptionSpelling> spelling{OptionSpelling::Cli};
}

void setOptionSpelling(OptionSpelling s) { spelling.store(s); }

OptionSpelling optionSpelling() { return spelling.load(); }

std::string optionName(const std::string& cliName) {
  if (optionSpelling() == OptionSpelling::Cli) return cliName;
  std::string name = cliName.substr(cliName.find_first_not_of('-'));
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

std::string defineName(const std::string& name) {
  return optionSpelling() == OptionSpelling::Cli ? "-D " + name : "defines['" + name + "']";
}

std::string optionSetting(const std::string& cliName, const std::string& word) {
  return optionSpelling() == OptionSpelling::Cli ? cliName + " " + word : optionName(cliName) + "=\"" + word + "\"";
}

std::string firstFramesSetting(long long count) {
  return optionSpelling() == OptionSpelling::Cli ? "--frames 0:" + std::to_string(count - 1)
                                                  : "frames=range(" + std::to_string(count) + ")";
}

}  // namespace dicsynth
