#pragma once
// Images in any format OpenImageIO reads, through a module loaded on first use
// (libdicsynth_oiio.so beside the executable, built from files/oiio_module/): the dicsynth binary does
// not link OpenImageIO, whose ~250 shared libraries would cost every process ~0.18 s at start even
// when it only reads a TIFF and writes TIFF and EXR (which libtiff and OpenEXR do directly).
#include <string>
#include <string_view>

#include "files/image_io.h"

namespace dicsynth {

// decodeGrayImage's contract (files/image_io.h) for any format. Throws InputError("PATH: reason"),
// also when the module cannot be loaded (then naming it and why).
GrayImage readGrayImageWithOiio(const std::string& path, std::string_view bytes, bool* readPath);

// A function of the module by name (files/oiio_module/oiio_module.h), or null with `failure` saying why.
void* oiioModuleSymbol(const char* symbol, std::string& failure);

}  // namespace dicsynth
