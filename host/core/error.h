#pragma once
// Errors of dicsynth. Two families, told apart by the exit code the CLI maps them to:
//  - InputError: the user's input is wrong (scene, parameters, files). Its message already starts with
//    the place to fix, e.g. "scenes/plate.lua:12: Shape.Sphere: 'radius' must be > 0". Exit code 2.
//  - Error: anything else that stops a run (Vulkan failure, I/O failure, internal check). Its message
//    carries the C++ file:line where it was raised. Exit code 3.
#include <source_location>
#include <stdexcept>
#include <string>

namespace dicsynth {

// A place in a scene file, kept by every scene node so that late errors (missing texture found while
// preparing geometry) still point at the scene line that asked for it.
struct SourceLoc {
  std::string file;  // path as given by the user
  int line = 0;      // 1-based; 0 = unknown
  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  InputError(const SourceLoc& where, const std::string& message)
      : std::runtime_error(where.str() + ": " + message) {}
};

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message,
                 std::source_location here = std::source_location::current())
      : std::runtime_error(message + " [" + shortFile(here.file_name()) + ":" +
                           std::to_string(here.line()) + "]") {}

 private:
  static std::string shortFile(const char* path) {
    std::string p(path);
    auto pos = p.rfind("/host/");
    return pos == std::string::npos ? p : p.substr(pos + 1);
  }
};

// Internal invariant: a failure is a bug in dicsynth, not in the user's input.
#define DS_CHECK(cond, msg)                                                  \
  do {                                                                      \
    if (!(cond)) throw ::dicsynth::Error(std::string("internal check failed: ") + #cond + ": " + (msg)); \
  } while (0)

}  // namespace dicsynth
