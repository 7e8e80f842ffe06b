#pragma once
// Texture.Speckle: its parameters, parsing, value and bounds (the model and its arithmetic:
// host/texture/analytic_speckle.h). GLSL twin: shaders/textures/speckle.glsl.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/math.h"
#include "shared/kinds.h"
#include "texture/analytic_speckle.h"
#include "textures/wrap.h"

namespace dicsynth::textures {

/* ------------------------------------------------------------------------------------------------
Texture.Speckle: an analytic speckle in (u, v): dark disks of one radius from a seeded Boolean
(Poisson) model on a light background, decided exactly per sample; no image, no interpolation.
Model and formulas: host/texture/analytic_speckle.h.

  Parameter | Value   | Default | Meaning
  ----------+---------+---------+------------------------------------------------------------
  radius    | number  | 0.005   | disk radius in u units (fraction of the surface's u range),
            |         |         | > 0; on a w-wide rectangle a radius of ρ metres is ρ / w
  density   | number  | 0.5     | expected fraction of the area covered, in (0, 0.95]
  aspect    | number  | 1       | the surface's v length / u length (e.g. h / w of a
            |         |         | rectangle), so that disks are round on the surface
  seed      | integer | 1       | 0 … 2^32 − 1; the same seed gives the same disks everywhere
  dark      | number  | 0       | texture value inside the disks, >= 0
  light     | number  | 1       | texture value outside, >= 0
  wrap      | string  | "clamp" | "clamp": not periodic, the disks end at u, v = 0 and 1 (a seam
            |         |         | cuts them); "repeat", "repeatU", "repeatV": periodic in u and v,
            |         |         | u only, v only: the pattern continues across u = 1 → 0 (v = 1 → 0),
            |         |         | the cells per unit along it rounded to a whole number (the radius
            |         |         | then 1/(2·round(1/(2r))); texture/analytic_speckle.h)

Example:  Texture.Speckle { radius = 0.004; density = 0.5; aspect = 0.5; seed = 7; wrap = "repeatU" }
------------------------------------------------------------------------------------------------ */
struct Speckle {
  static constexpr TextureKind kKind = TextureKind::Speckle;
  static constexpr const char* kName = "Speckle";
  static constexpr const char* kConstructor = "Texture.Speckle";
  static constexpr std::array<const char*, 7> kKeys{"radius", "density", "aspect", "seed", "dark", "light", "wrap"};
  static constexpr const char* kTwin = "speckle";

  AnalyticSpeckle model;

  template <class Params>
  static Speckle parse(const Params& p, const std::filesystem::path&) {
    const long long seed = p.integer("seed").value_or(1);
    p.require(seed >= 0 && seed <= 0xffffffffLL, "seed", "an integer in 0 .. 2^32 - 1", double(seed));
    const TextureWrap wrap = parseWrap(p);
    Speckle s;
    try {
      s.model = makeAnalyticSpeckle(p.number("radius", 0.005), p.number("density", 0.5), p.number("aspect", 1.0),
                                    std::uint32_t(seed), p.number("dark", 0.0), p.number("light", 1.0),
                                    repeatsU(wrap), repeatsV(wrap));
    } catch (const InputError& e) {
      p.fail(e.what());
    }
    return s;
  }

  // The radius a periodic axis rounded (analytic_speckle.h, "Periodic axes"), said on stderr when
  // the scene loads: the value used is in no output file. Empty when nothing was rounded (to 1e-12).
  std::string loadNote() const {
    const AnalyticSpeckle& m = model;
    if (m.periodU_cells == 0 && m.periodV_cells == 0) return {};
    const double used = 1.0 / (2.0 * m.cellsPerUv.x);  // u units; the disks' radius is half a cell
    if (std::abs(used - m.radius_uv) <= 1e-12 * m.radius_uv && (m.periodU_cells == 0 || m.periodV_cells == 0)) return {};
    char text[320];
    const auto number = [&](double v) {
      std::snprintf(text, sizeof text, "%.9g", v);
      return std::string(text);
    };
    std::string note = "wrap rounds the radius " + number(m.radius_uv) + " to " + number(used) + " u units: ";
    if (m.periodU_cells > 0 && m.periodV_cells > 0)
      note += std::to_string(m.periodU_cells) + " x " + std::to_string(m.periodV_cells) +
              " disk diameters per unit u x v, the disks scaled by " + number(m.aspect * m.periodU_cells / m.periodV_cells) +
              " in v";
    else if (m.periodU_cells > 0)
      note += std::to_string(m.periodU_cells) + " disk diameters around u";
    else
      note += std::to_string(m.periodV_cells) + " disk diameters along v";
    return note;
  }

  double at(dvec2 uv) const { return speckleTextureValue(model, uv); }
  double maxValue() const { return std::max(std::abs(model.light), std::abs(model.dark)); }
  double slopePerUv() const { return 0; }  // steps, as the targets'
};

}  // namespace dicsynth::textures
