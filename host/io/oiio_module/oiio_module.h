#pragma once
// The interface of libdicsynth_oiio.so (io/oiio_reader.h loads it): one C-named function, built by
// the same compiler and standard library as its callers, so it may take C++ objects.
#include <string>

#include "io/image_io.h"

namespace dicsynth {

inline constexpr const char* kOiioModuleFile = "libdicsynth_oiio.so";
inline constexpr const char* kOiioReadGraySymbol = "dicsynth_oiio_read_gray";

// Fills `image` per readGrayImage's contract and returns true, or sets `error` ("cannot read image:
// ...", without the path) and returns false. Never throws.
using ReadGrayFn = bool (*)(const char* path, GrayImage* image, std::string* error);

}  // namespace dicsynth
