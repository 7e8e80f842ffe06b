#pragma once
// The modules dicsynth loads on first use (libdicsynth_oiio.so, libdicsynth_vtk.so): built beside
// the binary that holds dicsynth's code — the dicsynth executable, a test or bench program, or the
// Python module (dicsynth*.so) — and loaded from there once per process, never unloaded (the
// libraries behind them keep threads, caches and singletons).
#include <filesystem>
#include <mutex>
#include <string>

namespace dicsynth {

std::filesystem::path codeFolder();

// The GNU build ID (hex) of that binary: it changes whenever the code is rebuilt differently, so
// files that only this exact code may read back (core/cache_dir.h's caches) are keyed by it. ""
// when the binary carries none (linked without --build-id).
std::string codeBuildId();
// codeBuildId(), or "none": as --version says it and the files record it (dicsynth:build, a sweep
// manifest's "build").
std::string codeBuildIdText();

class LoadableModule {
 public:
  explicit LoadableModule(std::string fileName) : fileName_(std::move(fileName)) {}
  // The module's function `name`, loading the module on the first call; null with `failure`
  // saying why (the module cannot be loaded, or lacks the function: a stale build). Thread-safe.
  void* symbol(const char* name, std::string& failure);

 private:
  std::string fileName_, path_, loadFailure_;
  std::once_flag once_;
  void* handle_ = nullptr;
};

}  // namespace dicsynth
