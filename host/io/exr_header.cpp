#include "io/exr_header.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <exception>

namespace dicsynth {

std::optional<std::string> exrStringAttributeWithChannel(const std::string& path, const std::string& name,
                                                         std::initializer_list<const char*> channels) {
  try {
    const Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    if (std::none_of(channels.begin(), channels.end(), [&](const char* c) { return header.channels().findChannel(c); }))
      return std::nullopt;
    if (const auto* a = header.findTypedAttribute<Imf::StringAttribute>(name)) return a->value();
  } catch (const std::exception&) {  // not an EXR, damaged, unreadable: no attribute
  }
  return std::nullopt;
}

}  // namespace dicsynth
