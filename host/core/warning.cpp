#include "core/warning.h"

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <utility>

namespace dicsynth {
namespace {

// The live captures. One mutex guards the list and every capture's texts.
struct Captures {
  std::mutex mutex;
  std::vector<WarningCapture*> live;
};

Captures& captures() {
  static Captures c;
  return c;
}

}  // namespace

void say(bool warning, const std::string& text) {
  Captures& c = captures();
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    if (!c.live.empty()) {
      for (WarningCapture* capture : c.live) capture->messages_.push_back({warning, text});
      return;
    }
  }
  // One write of the whole line (a scene's print may hold any byte), flushed at once.
  const std::string line = (warning ? "dicsynth: warning: " : "") + text + "\n";
  std::fwrite(line.data(), 1, line.size(), stderr);
  std::fflush(stderr);
}

void warn(const std::string& text) { say(true, text); }
void note(const std::string& line) { say(false, line); }

WarningCapture::WarningCapture() {
  Captures& c = captures();
  std::lock_guard<std::mutex> lock(c.mutex);
  c.live.push_back(this);
}

WarningCapture::~WarningCapture() {
  Captures& c = captures();
  std::lock_guard<std::mutex> lock(c.mutex);
  c.live.erase(std::find(c.live.begin(), c.live.end(), this));
}

std::vector<WarningCapture::Message> WarningCapture::takeMessages() {
  std::lock_guard<std::mutex> lock(captures().mutex);
  return std::exchange(messages_, {});
}

std::vector<std::string> WarningCapture::take() {
  std::vector<std::string> warnings;
  for (Message& m : takeMessages())
    if (m.warning) warnings.push_back(std::move(m.text));
  return warnings;
}

}  // namespace dicsynth
