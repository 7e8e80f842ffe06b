#pragma once
// Reading a ground-truth EXR back in tests: every float channel by name, and objectId as uint.
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace dicsynth::test {

struct ExrContents {
  OIIO::ImageSpec spec;
  std::map<std::string, std::vector<float>> floats;  // float channels by name
  std::vector<std::uint32_t> objectId;
};

inline ExrContents readExr(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE_MESSAGE(in, OIIO::geterror());
  ExrContents exr{in->spec(), {}, {}};
  const std::size_t n = std::size_t(exr.spec.width) * std::size_t(exr.spec.height);
  for (int c = 0; c < exr.spec.nchannels; ++c) {
    const std::string& name = exr.spec.channelnames[c];
    if (name == "objectId") {
      exr.objectId.resize(n);
      REQUIRE(in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::UINT, exr.objectId.data()));
    } else {
      auto& values = exr.floats[name];
      values.resize(n);
      REQUIRE(in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, values.data()));
    }
  }
  return exr;
}


}  // namespace dicsynth::test
