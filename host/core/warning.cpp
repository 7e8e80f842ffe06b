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

void warn(const std::string& text) {
  Captures& c = captures();
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    if (!c.live.empty()) {
      for (WarningCapture* capture : c.live) capture->texts_.push_back(text);
      return;
    }
  }
  std::fprintf(stderr, "dicsynth: warning: %s\n", text.c_str());
}

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

std::vector<std::string> WarningCapture::take() {
  std::lock_guard<std::mutex> lock(captures().mutex);
  return std::exchange(texts_, {});
}

}  // namespace dicsynth
