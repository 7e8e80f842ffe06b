// core/termination.h: a signal's cleanup waits for a set of renames under holdTermination, so that a
// set of files (an image and its ground truth, a manifest's two files, a rig's calibration files)
// ends complete or absent, never split. The faults audit of 2026-11-28 split them with a SIGTERM
// between two renames (held open there by strace).
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "core/atomic_file.h"
#include "core/termination.h"
#include "temp_folder.h"

using namespace dicsynth;

TEST_CASE("termination: a SIGTERM during a set of renames ends the process after the set, with no temporary left") {
  test::TempFolder dir;
  const std::string first = dir.file("image.tif"), second = dir.file("image.exr");
  // A child process: the cleanup ends the process it runs in. The signal comes between the two
  // renames, and the second rename comes 0.3 s later, when the cleanup has long had the signal.
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    try {
      removeTemporariesOnTermination();
      AtomicFile a(first), b(second);
      writeText(a, "tiff");
      writeText(b, "exr");
      {
        const auto hold = holdTermination();
        a.commit();
        ::kill(::getpid(), SIGTERM);
        ::usleep(300000);
        b.commit();
      }
      ::usleep(3000000);  // the cleanup ends the process here
      ::_exit(10);
    } catch (...) {
      ::_exit(11);
    }
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  CHECK(std::filesystem::exists(first));
  CHECK(std::filesystem::exists(second));  // the cleanup had removed its temporary before the rename
  int left = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) left += e.path().filename().string()[0] == '.';
  CHECK(left == 0);
}
