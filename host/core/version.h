#pragma once
// The version of dicsynth, recorded in every output file's metadata. Keep in step with
// project(VERSION) in CMakeLists.txt and the --version flag in host/cli/main.cpp.
namespace dicsynth {
inline constexpr const char* kVersion = "0.1.0";
}  // namespace dicsynth
