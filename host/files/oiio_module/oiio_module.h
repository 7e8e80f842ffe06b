#pragma once
// The interface of libdicsynth_oiio.so (files/oiio_reader.h, io/preview.h load it): C-named functions,
// built by the same compiler and standard library as their callers, so they may take C++ objects.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "files/image_io.h"

namespace dicsynth {

inline constexpr const char* kOiioModuleFile = "libdicsynth_oiio.so";
inline constexpr const char* kOiioReadGraySymbol = "dicsynth_oiio_read_gray";

// Fills `image` per decodeGrayImage's contract (files/image_io.h) from the `size` bytes at `bytes`
// (the content of the file `path`) and returns true, or sets `error` ("cannot read image: ...",
// without the path) and returns false. `*readPath` says whether the file was read by its path
// instead (a format whose reader takes no memory input). Never throws.
using ReadGrayFn = bool (*)(const char* path, const char* bytes, std::size_t size, GrayImage* image,
                            std::string* error, bool* readPath);

inline constexpr const char* kOiioPreviewSymbol = "dicsynth_oiio_preview";

// Pictures of the layers of an EXR (io/preview.h has the contract).
struct PreviewRequest {
  std::string exrPath;    // the EXR to show
  std::string outputDir;  // existing folder for the PNGs
  std::string stem;       // PNG names: <stem>.<layer>.png
  int maxWidth = 800;     // the picture's image part is at most this wide (px), decimated by an integer
  std::string fontPath;   // TrueType font for the labels; "" or missing: OpenImageIO's own search
  // Writes one picture's PNG bytes to `path` completely (or not at all) and returns true; false
  // stops the preview, the caller keeping why. The module encodes, the caller writes: its files are
  // checked for a full disk and removed on a signal as every file of a run (core/atomic_file.h).
  std::function<bool(const std::string& path, const std::vector<unsigned char>& png)> write;
};
struct PreviewResult {
  std::vector<std::string> written;  // paths of the PNGs
  std::vector<std::string> skipped;  // "channel or layer: why"
};
using PreviewFn = bool (*)(const PreviewRequest* request, PreviewResult* result, std::string* error);

}  // namespace dicsynth
