// dicsynth: synthetic images with exact ground truth for experimental mechanics.
// Maps every failure to a one-line message on stderr and a documented exit code (commands.h).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <system_error>

#include "cli/commands.h"
#include "cli/error_line.h"
#include "cli/options.h"
#include "cli/suggestion.h"
#include "core/error.h"
#include "core/module_folder.h"
#include "core/phase_timer.h"
#include "core/termination.h"
#include "core/version.h"
#include "core/warning.h"
#include "io/zip_deflate.h"

namespace {

// A standard descriptor the caller closed (`>&-`, `2>&-`, some daemons and job schedulers) is the
// lowest free number, which the next open() takes: a writer thread's temporary file became fd 1 and
// the run's own listing lines landed inside an output TIFF (and on the GPU, inside lavapipe's
// device memory; the hostile-input trial of 2026-11-29). Each closed one is held by /dev/null,
// opened read-only for 1 and 2 so that writing there still fails (a closed stdout stays exit 3,
// docs/commands.md), and for reading for 0.
void holdClosedStandardDescriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int opened = ::open("/dev/null", O_RDONLY);
    if (opened >= 0 && opened != fd) {  // fd was free, so open() took it unless it raced: make sure
      ::dup2(opened, fd);
      ::close(opened);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dicsynth;
  holdClosedStandardDescriptors();  // before anything opens a file
  phaseDone(nullptr);  // DICSYNTH_TIMINGS=1: phases are timed from here
  removeTemporariesOnTermination();  // before any thread: SIGTERM, SIGINT, SIGHUP clean up first
  // A file-size limit (`ulimit -f`, common in CI sandboxes) raises SIGXFSZ, whose default kills the
  // process mid-write and left its temporary files (exit 153; the CI trial of 2026-11-29). Ignored,
  // the write fails with EFBIG instead, which every writer reports: exit 3, temporaries removed.
  std::signal(SIGXFSZ, SIG_IGN);
  // stdout line by line also into a file or pipe (a Slurm log, `> run.log`): each "written" line is
  // out once its files are complete. Fully buffered, a run ended by SIGTERM lost the lines of its
  // last finished frames and cut the last one mid-path (4 KB blocks; the new-user trial of
  // 2026-11-28: 4 finished frames unlisted). A few lines per frame: no cost to measure.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  CLI::App app{"dicsynth: ray-traced synthetic images and ground truth for stereo DIC", "dicsynth"};
  app.require_subcommand(1);
  // With the deflate that compresses zip EXRs (io/zip_deflate.h): it decides their writing time.
  // The build ID too: the version alone names many builds, and the files record the build
  // (dicsynth:build; the reproducibility trial of 2026-11-29).
  app.set_version_flag("--version", [] {
    return std::string("dicsynth ") + kVersion + " (build " + codeBuildIdText() +
           "; EXR zip: " + zipDeflateEngine() + ")";
  });
  cli::RunFn run;
  cli::addRenderCommand(app, run);
  cli::addCompareCommand(app, run);
  cli::addDevicesCommand(app, run);
  cli::addSpeckleCommand(app, run);
  cli::addPreviewCommand(app, run);
  cli::addBenchCommand(app, run);
  cli::addSweepCommand(app, run);
  cli::decimalIntegers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string hint = cli::suggestion(app, argc, argv);
    // "files is required" alone (`dicsynth preview --width 600`, the docs walk of 2026-11-29): where
    // the command's arguments are listed.
    if (hint.empty() && dynamic_cast<const CLI::RequiredError*>(&e) && argc >= 2)
      for (CLI::App* sub : app.get_subcommands({}))
        if (sub->get_name() == argv[1]) hint = std::string(" (dicsynth ") + argv[1] + " --help lists its arguments)";
    std::fprintf(stderr, "dicsynth: error: %s%s\n", e.what(), hint.c_str());
    return cli::kExitBadInput;
  }
  try {
    const int code = run ? run() : cli::kExitBadInput;
    // What a run printed on stdout (the files it wrote) must have arrived: a full device or a closed
    // stdout lost the list silently with exit 0 (the CI trial of 2026-11-29).
    const bool flushed = std::fflush(stdout) == 0;
    const int flushError = errno;
    if (!flushed || std::ferror(stdout)) {
      std::fprintf(stderr, "dicsynth: error: could not write to stdout%s%s (the lines listing what was written are lost)\n",
                   flushed ? "" : ": ", flushed ? "" : std::strerror(flushError));
      return code == cli::kExitOk ? cli::kExitFailure : code;
    }
    if (const std::size_t warnings = warningsWritten(); code == cli::kExitOk && cli::strictWarnings() && warnings > 0) {
      std::fprintf(stderr, "dicsynth: error: --strict: the run said %zu warning%s (%s)\n", warnings,
                   warnings == 1 ? "" : "s", cli::nothingWritten() ? "it writes no file" : "its files are written");
      return cli::kExitStrictWarnings;
    }
    return code;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", cli::errorLine(e.what()).c_str());
    return cli::kExitBadInput;
  } catch (const std::bad_alloc&) {
    // "std::bad_alloc" alone said nothing of the cause (the hostile-input trial of 2026-11-29).
    std::fprintf(stderr, "dicsynth: error: out of memory (std::bad_alloc): the run needed more than the system or its "
                         "limits (ulimit -v, a control group's memory limit) allow: --downscale, fewer pixels or --layers "
                         "image take less\n");
    return cli::kExitFailure;
  } catch (const std::system_error& e) {
    // A thread that could not start: "Resource temporarily unavailable" alone (the same trial).
    const bool thread = e.code() == std::errc::resource_unavailable_try_again;
    std::fprintf(stderr, "%s%s\n", cli::errorLine(e.what()).c_str(),
                 thread ? " (a thread could not be started: a limit on processes or address space, ulimit -u or -v?)" : "");
    return cli::kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", cli::errorLine(e.what()).c_str());
    return cli::kExitFailure;
  }
}
