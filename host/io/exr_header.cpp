#include "io/exr_header.h"

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <exception>

namespace dicsynth {

std::optional<std::string> exrStringAttribute(const std::string& path, const std::string& name) {
  try {
    const Imf::InputFile file(path.c_str());
    if (const auto* a = file.header().findTypedAttribute<Imf::StringAttribute>(name)) return a->value();
  } catch (const std::exception&) {  // not an EXR, damaged, unreadable: no attribute
  }
  return std::nullopt;
}

}  // namespace dicsynth
