#pragma once
// Warnings: what a run says about its input or its machine without stopping (a -D value that looks
// like a decimal comma, a camera that sees nothing, a cache that could not be written).
//
// By default a warning is one line on stderr, "dicsynth: warning: <text>". While a WarningCapture
// lives, warnings are collected by it instead: the Python module turns them into Python warnings
// (dicsynth.DicsynthWarning), which a notebook shows and `warnings` filters, where a line on the process's
// stderr would be lost. Warnings may come from any thread; every capture alive when one is raised
// receives it (two renders running at once in one process each see the other's warnings).
#include <string>
#include <vector>

namespace dicsynth {

void warn(const std::string& text);

class WarningCapture {
 public:
  WarningCapture();
  ~WarningCapture();
  WarningCapture(const WarningCapture&) = delete;
  WarningCapture& operator=(const WarningCapture&) = delete;

  // The warnings raised since construction or the last take(), in the order raised.
  std::vector<std::string> take();

 private:
  friend void warn(const std::string& text);
  std::vector<std::string> texts_;  // guarded by the registry's mutex (warning.cpp)
};

}  // namespace dicsynth
