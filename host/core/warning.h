#pragma once
// Warnings: what a run says about its input or its machine without stopping (a -D value that looks
// like a decimal comma, a camera that sees nothing, a cache that could not be written). Notes: the
// other lines a run says on stderr as it goes (a scene's print, a Nurbs.deform fit's report, the
// precision `auto` chose).
//
// By default a warning is one line on stderr, "dicsynth: warning: <text>", and a note the line
// itself. While a WarningCapture lives, both are collected by it instead, in the order said: the
// Python module turns warnings into Python warnings (dicsynth.DicsynthWarning), which a notebook
// shows and `warnings` filters, and writes notes to sys.stderr, where lines on the process's stderr
// would be lost. They may come from any thread; every capture alive when one is said receives it
// (two renders running at once in one process each see the other's).
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace dicsynth {

void warn(const std::string& text);
// warn(text), unless warnings of `kind` were said `most` times already: per process, or per capture
// while one lives (a Python call: each call may say them again). The last one said ends with
// `lastNote` (" (further ... not reported)"). For warnings a long run would repeat for every frame.
void warnAtMost(const std::string& kind, int most, const std::string& text, const std::string& lastNote = "");
// `line` without its newline.
void note(const std::string& line);
// note(line), once per process (per capture while one lives) for each `line`: what a scene says
// where it is evaluated again for every frame (a periodic speckle's rounded radius was said six
// times by a six-frame run: the docs walk of 2026-11-29).
void noteOnce(const std::string& line);
// How many warnings this process wrote on stderr (not those a capture took): what --strict judges.
std::size_t warningsWritten();

class WarningCapture {
 public:
  struct Message {
    bool warning;  // false: a note
    std::string text;
  };
  WarningCapture();
  ~WarningCapture();
  WarningCapture(const WarningCapture&) = delete;
  WarningCapture& operator=(const WarningCapture&) = delete;

  // The warnings and notes said since construction or the last take, in the order said.
  std::vector<Message> takeMessages();
  // takeMessages()'s warnings, the notes dropped (for callers that judge warnings only).
  std::vector<std::string> take();

 private:
  friend void say(bool warning, const std::string& text);
  // warnAtMost and noteOnce (warning.cpp).
  friend void sayAtMost(bool warning, const std::string& kind, int most, const std::string& text, const std::string& lastNote);
  // Guarded by the registry's mutex (warning.cpp).
  std::vector<Message> messages_;
  std::map<std::string, int> said_;  // warnAtMost's counts while this capture lives
};

}  // namespace dicsynth
