#include "io/exr_header.h"

#include <OpenEXR/ImfChannelList.h>
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

bool exrHasAnyChannel(const std::string& path, std::initializer_list<const char*> channels) {
  try {
    const Imf::InputFile file(path.c_str());
    for (const char* c : channels)
      if (file.header().channels().findChannel(c)) return true;
  } catch (const std::exception&) {
  }
  return false;
}

}  // namespace dicsynth
