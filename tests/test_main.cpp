// The doctest entry point of the whole suite (one executable, one CTest test per TEST_CASE).
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdlib>

int main(int argc, char** argv) {
#ifdef DS_TEST_CACHE_DIR
  // What dicsynth caches (prepared textures, pipelines, the precision calibration) goes to the build
  // folder, not the user's cache folder (Figure 1's prepared textures alone are ~130 MB), for this
  // process and the CLI runs it starts; a DICSYNTH_CACHE_DIR the caller set is kept.
  setenv("DICSYNTH_CACHE_DIR", DS_TEST_CACHE_DIR, 0);
#endif
  doctest::Context context(argc, argv);
  return context.run();
}
