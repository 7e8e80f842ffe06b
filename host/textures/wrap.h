#pragma once
// The `wrap` key of Texture.File and Texture.Speckle: which of u and v are periodic (the texture
// continues across u = 1 → 0, v = 1 → 0). One vocabulary and one message for both kinds.
#include <string>

#include "texture/bspline.h"

namespace dicsynth::textures {

template <class Params>
TextureWrap parseWrap(const Params& p) {
  const std::string wrap = p.string("wrap").value_or("clamp");
  if (wrap == "clamp") return TextureWrap::Clamp;
  if (wrap == "repeat") return TextureWrap::Repeat;
  if (wrap == "repeatU") return TextureWrap::RepeatU;
  if (wrap == "repeatV") return TextureWrap::RepeatV;
  p.fail("'wrap' must be \"clamp\", \"repeat\", \"repeatU\" or \"repeatV\", got \"" + wrap + "\"");
}

}  // namespace dicsynth::textures
