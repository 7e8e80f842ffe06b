#pragma once
// Texture.File: its parameters, parsing (the file is resolved against the scene's folder and must
// be readable), its prepared image (filled by prepare: geometry/prepare.cpp), value, bounds and GPU
// data. GLSL twin: shaders/textures/file.glsl. The B-spline kernels: host/texture/bspline.h.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "shared/kinds.h"
#include "texture/bspline.h"
#include "textures/wrap.h"

namespace dicsynth::textures {

/* ------------------------------------------------------------------------------------------------
Texture.File: an image (e.g. a speckle pattern) glued on the surface's (u, v) parameters.

  Parameter     | Value   | Default  | Meaning
  --------------+---------+----------+---------------------------------------------------------
  fileName      | string  | required | image file; a relative path is relative to the scene
                |         |          | file's folder, not to the working directory
  interpolation | string  | "cubic"  | "cubic": interpolating cubic B-spline (4×4 texels);
                |         |          | "quintic": interpolating quintic B-spline (6×6 texels),
                |         |          | less interpolation bias (texture/bspline.h, docs/scene-language.md)
  wrap          | string  | "clamp"  | the borders: "clamp": (u, v) outside [0, 1] read the edge, the
                |         |          | spline mirrored at it; "repeat": periodic in u and v, the spline
                |         |          | continues across u = 1 → 0 and v = 1 → 0 (seamless tiles of a
                |         |          | Shape.Plane); "repeatU": periodic in u only (around a sphere or
                |         |          | cylinder), v clamped; "repeatV": v only

The file must exist and be readable when the constructor runs (the error names the line); it is
decoded later, when the scene is prepared.

Example:  Texture.File { fileName = "speckle.tif"; interpolation = "quintic"; wrap = "repeatU" }
------------------------------------------------------------------------------------------------ */
struct File {
  static constexpr TextureKind kKind = TextureKind::File;
  static constexpr const char* kName = "File";
  static constexpr const char* kConstructor = "Texture.File";
  static constexpr std::array<const char*, 3> kKeys{"fileName", "interpolation", "wrap"};
  static constexpr const char* kTwin = "file";

  std::string path;  // resolved (a relative fileName resolves against the scene's folder)
  Interpolation interpolation = Interpolation::Cubic;
  TextureWrap wrap = TextureWrap::Clamp;
  // Prepared (geometry/prepare.cpp): the image's B-spline coefficients, shared with
  // PreparedScene::textures[index] (which the GPU uploads), and that index.
  std::shared_ptr<const std::vector<double>> coefficients;
  int width = 0, height = 0;
  int index = -1;

  template <class Params>
  static File parse(const Params& p, const std::filesystem::path& sceneDir) {
    File f;
    const std::optional<std::string> fileName = p.string("fileName");
    if (!fileName) p.fail("missing required 'fileName'");
    if (fileName->empty()) p.fail("'fileName' must not be empty");
    const std::string interpolation = p.string("interpolation").value_or("cubic");
    if (interpolation == "cubic")
      f.interpolation = Interpolation::Cubic;
    else if (interpolation == "quintic")
      f.interpolation = Interpolation::Quintic;
    else
      p.fail("'interpolation' must be \"cubic\" or \"quintic\", got \"" + interpolation + "\"");
    f.wrap = parseWrap(p);
    // Resolve against the scene's folder, then check the file can be read.
    const std::filesystem::path given(*fileName);
    const std::filesystem::path resolved = given.is_absolute() ? given : sceneDir / given;
    f.path = resolved.string();
    std::string name = "'" + *fileName + "'";
    if (f.path != *fileName) name += " (resolved to '" + f.path + "')";
    std::error_code ec;
    if (std::filesystem::is_directory(resolved, ec)) p.fail("cannot read " + name + ": it is a folder");
    if (std::filesystem::exists(resolved, ec) && !std::filesystem::is_regular_file(resolved, ec))
      p.fail("cannot read " + name + ": not a regular file");
    std::FILE* file = std::fopen(f.path.c_str(), "rb");
    if (file == nullptr) p.fail("cannot read " + name + ": " + std::strerror(errno));
    std::fclose(file);
    return f;
  }

  // The interpolated value at (u, v) (each clamped to [0, 1] or taken modulo 1: `wrap`), from the
  // prepared coefficients.
  double at(dvec2 uv) const {
    return bsplineLookup(coefficients->data(), width, height, textureCoordinate(uv.x, repeatsU(wrap)),
                         textureCoordinate(uv.y, repeatsV(wrap)), interpolation, wrap);
  }
  // A B-spline is a convex combination of its coefficients: |value| ≤ max |c|.
  double maxValue() const {
    double m = 0;
    for (double c : *coefficients) m = std::max(m, std::abs(c));
    return m;
  }
  // The B-spline's slope is bounded by the largest difference of neighbouring coefficients per
  // texel (its derivative is a quadratic B-spline, a convex combination, of those differences),
  // times texels per unit (u, v); along an axis that repeats, the last and first coefficients are
  // neighbours too.
  double slopePerUv() const {
    const std::vector<double>& c = *coefficients;
    double sx = 0, sy = 0;
    const auto w = std::size_t(width), h = std::size_t(height);
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const double here = c[y * w + x];
        if (x + 1 < w) sx = std::max(sx, std::abs(c[y * w + x + 1] - here));
        if (y + 1 < h) sy = std::max(sy, std::abs(c[(y + 1) * w + x] - here));
      }
    // The seam's pairs apart, instead of a modulo per texel in the loop above.
    if (repeatsU(wrap))
      for (std::size_t y = 0; y < h; ++y) sx = std::max(sx, std::abs(c[y * w] - c[y * w + w - 1]));
    if (repeatsV(wrap))
      for (std::size_t x = 0; x < w; ++x) sy = std::max(sy, std::abs(c[x] - c[(h - 1) * w + x]));
    return std::max(sx * double(width), sy * double(height));
  }
};

}  // namespace dicsynth::textures
