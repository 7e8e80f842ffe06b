#pragma once
// Runs the dicsynth binary (DS_BINARY) as a user would, capturing its exit code, stdout and stderr.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "temp_folder.h"

namespace dicsynth::test {

struct CliResult {
  int exitCode = -1;  // -1 when the process did not exit normally (crash, signal)
  std::string out, err;
};

// `arguments` is appended to the binary path as shell words (quote paths with spaces yourself).
inline CliResult runCli(const std::string& arguments) {
  TempFolder capture;
  const std::string out = capture.file("out"), err = capture.file("err");
  const std::string command = std::string(DS_BINARY) + " " + arguments + " >" + out + " 2>" + err;
  const int status = std::system(command.c_str());
  CliResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readBytes(out);
  r.err = readBytes(err);
  return r;
}

}  // namespace dicsynth::test
