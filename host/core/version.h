#pragma once
// The version of dicsynth, recorded in every output file's metadata and printed by --version.
// Single source: project(VERSION) in CMakeLists.txt, passed in as DS_VERSION.
namespace dicsynth {
inline constexpr const char* kVersion = DS_VERSION;
}  // namespace dicsynth
