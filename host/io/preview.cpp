#include "io/preview.h"

#include <cstdio>
#include <exception>
#include <string_view>

#include "core/atomic_file.h"
#include "core/error.h"
#include "files/oiio_module/oiio_module.h"
#include "files/oiio_reader.h"

namespace dicsynth {

PreviewFiles previewExr(const std::string& exrPath, const std::string& outputDir, const std::string& stem, int maxWidth) {
  std::string failure;
  const auto preview = reinterpret_cast<PreviewFn>(oiioModuleSymbol(kOiioPreviewSymbol, failure));
  if (!preview) throw InputError(exrPath + ": a preview needs OpenImageIO's module: " + failure);
  PreviewRequest request;
  request.exrPath = exrPath;
  request.outputDir = outputDir;
  request.stem = stem;
  request.maxWidth = maxWidth;
  // Debian's fonts-dejavu-core (scripts/install-deps.sh); OpenImageIO searches its own otherwise.
  request.fontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  // A picture that cannot be written (a full disk: Error, exit 3) stops the preview with that error.
  std::exception_ptr writeFailure;
  request.write = [&writeFailure](const std::string& path, const std::vector<unsigned char>& png) {
    try {
      writeTextAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
      return true;
    } catch (...) {
      writeFailure = std::current_exception();
      return false;
    }
  };
  PreviewResult result;
  std::string error;
  if (!preview(&request, &result, &error)) {
    // Nothing half-done: this file's pictures written before the failure go too.
    for (const std::string& png : result.written) std::remove(png.c_str());
    if (writeFailure) std::rethrow_exception(writeFailure);
    throw InputError(error);
  }
  return {std::move(result.written), std::move(result.skipped)};
}

}  // namespace dicsynth
