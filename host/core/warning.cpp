#include "core/warning.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
#include <utility>

#include "core/source_place.h"

namespace dicsynth {
namespace {

// The live captures. One mutex guards the list and every capture's texts.
struct Captures {
  std::mutex mutex;
  std::vector<WarningCapture*> live;
  std::map<std::string, int> said;  // warnAtMost's counts with no capture alive
};

// Counts one more warning of a kind against `most`: the text to say, or none once `most` were said.
std::optional<std::string> counted(int& count, int most, const std::string& text, const std::string& lastNote) {
  if (count >= most) return std::nullopt;
  ++count;
  return count == most ? text + lastNote : text;
}

std::atomic<std::size_t> written{0};  // warnings written on stderr

void writeLine(bool warning, const std::string& text) {
  if (warning) ++written;
  // One write of the whole line (a scene's print may hold any byte), flushed at once. A warning that
  // names a scene line carries its word after the place, as an error does: "PATH:LINE: warning: ..."
  // (it was "dicsynth: warning: PATH:LINE: ...", a line editors did not take for a place).
  const std::string line = (warning ? withKind("warning", text) : text) + "\n";
  std::fwrite(line.data(), 1, line.size(), stderr);
  std::fflush(stderr);
}

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
  writeLine(warning, text);
}

void warn(const std::string& text) { say(true, text); }

// say(), at most `most` times for a `kind` (per process, or per capture while one lives).
void sayAtMost(bool warning, const std::string& kind, int most, const std::string& text, const std::string& lastNote) {
  Captures& c = captures();
  std::optional<std::string> line;
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    if (!c.live.empty()) {
      for (WarningCapture* capture : c.live)
        if (const auto said = counted(capture->said_[kind], most, text, lastNote)) capture->messages_.push_back({warning, *said});
      return;
    }
    line = counted(c.said[kind], most, text, lastNote);
  }
  if (line) writeLine(warning, *line);
}

void warnAtMost(const std::string& kind, int most, const std::string& text, const std::string& lastNote) {
  sayAtMost(true, kind, most, text, lastNote);
}

void note(const std::string& line) { say(false, line); }

void noteOnce(const std::string& line) { sayAtMost(false, "note: " + line, 1, line, ""); }

std::size_t warningsWritten() { return written; }

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
