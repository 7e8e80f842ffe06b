// dicsynth preview FILE.exr... [-o DIR] [--width PX]: PNG pictures of every ground-truth layer of
// each file (io/preview.h): DIR/<file stem>.<layer>.png. DIR defaults to a folder "preview" beside
// the first file, created if missing. Prints each picture written and what was skipped, and why.
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "job/render_job.h"
#include "io/preview.h"

namespace dicsynth::cli {
namespace {

struct PreviewOptions {
  std::vector<std::string> files;
  std::string outputDir;
  int width = 800;
};

int runPreview(const PreviewOptions& options) {
  if (options.width < 16 || options.width > 16384)
    throw InputError("preview: --width " + std::to_string(options.width) + ": must be in 16..16384 (px)");
  for (const std::string& file : options.files) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file + ": no such file (or not a regular file)");
  }
  // The pictures are named by the file's stem: two files of one stem would overwrite each other's.
  std::map<std::string, std::string> stems;
  for (const std::string& file : options.files) {
    const std::string stem = std::filesystem::path(file).stem().string();
    if (const auto [it, fresh] = stems.emplace(stem, file); !fresh)
      throw InputError("preview: " + it->second + " and " + file + " would both be drawn as " + stem +
                       ".<layer>.png: preview them into separate folders (-o)");
  }
  const std::string dir = options.outputDir.empty()
                              ? (std::filesystem::path(options.files.front()).parent_path() / "preview").string()
                              : options.outputDir;
  checkOutputWritable(dir);
  std::error_code ec;
  const bool created = !std::filesystem::exists(dir, ec);
  const std::filesystem::path existing = nearestExistingFolder(dir);
  createOutputDir(dir);
  removeStaleTemporaries(dir);  // a killed run's pictures in the making (as render does in its folder)
  std::vector<std::string> written;
  try {
    for (const std::string& file : options.files) {
      const PreviewFiles files = previewExr(file, dir, std::filesystem::path(file).stem().string(), options.width);
      written.insert(written.end(), files.written.begin(), files.written.end());
      for (const std::string& png : files.written) std::printf("%s\n", png.c_str());
      for (const std::string& why : files.skipped) std::printf("%s: skipped %s\n", file.c_str(), why.c_str());
    }
  } catch (...) {
    // A folder the failed run made goes, with the pictures of the files before the failing one. In a
    // folder that was there, those complete pictures stay (the failing file's own are removed by
    // previewExr).
    if (created) {
      for (const std::string& png : written) std::filesystem::remove(png, ec);
      removeCreatedFolders(dir, existing);  // with the folders above it that it made; only when empty
    }
    throw;
  }
  return kExitOk;
}

}  // namespace

void addPreviewCommand(CLI::App& root, RunFn& run) {
  auto options = std::make_shared<PreviewOptions>();
  auto* sub = root.add_subcommand("preview", "PNG pictures of the ground-truth layers of EXR files");
  sub->add_option("files", options->files, "EXR files (dicsynth's, or any: each float channel is shown); a sensor TIFF is shown in DN")->required();
  sub->add_option("-o,--output", options->outputDir, "Folder for the PNGs (default: preview/ beside the first file)");
  sub->add_option("--width", options->width, "Largest width of a picture's image part, px (every k-th pixel shown)")
      ->capture_default_str();
  sub->callback([&run, options] { run = [options] { return runPreview(*options); }; });
}

}  // namespace dicsynth::cli
