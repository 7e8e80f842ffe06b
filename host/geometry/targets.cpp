#include "geometry/targets.h"

#include "core/error.h"

namespace dicsynth {

TargetLayout targetLayout(TextureKind kind, const textures::TargetPattern& p) {
  DS_CHECK(isTargetTexture(kind), "targetLayout: not a target texture");
  DS_CHECK(p.cols >= 1 && p.rows >= 1 && p.spacing_m > 0 && p.border_m >= 0, "targetLayout: invalid pattern");
  const double s = p.spacing_m, b = p.border_m;
  TargetLayout layout;
  layout.kind = kind;
  layout.pattern = p;
  TargetTexture& t = layout.texture;
  t.kind = int(kind);
  t.cols = p.cols;
  t.rows = p.rows;
  t.dark = p.dark;
  t.light = p.light;

  // Top-left corner of the rectangle in the target frame, and its size.
  dvec2 topLeft_m;
  if (kind == TextureKind::Checkerboard) {
    // The first inner corner is one square right of and below the squares' top-left corner.
    DS_CHECK(p.cols >= 2 && p.rows >= 2, "targetLayout: a checkerboard needs 2 x 2 squares");
    topLeft_m = dvec2(-s - b);
    layout.size_m = dvec2(p.cols * s, p.rows * s) + 2.0 * b;
    layout.perRow = p.cols - 1;
    layout.rows = p.rows - 1;
  } else {
    // Dots span from the first centre minus r to the last centre plus r; in an asymmetric grid
    // the odd rows reach s further right.
    const double r = p.radius_m;
    const double lastX = p.asymmetric ? (2.0 * (p.cols - 1) + (p.rows > 1 ? 1.0 : 0.0)) * s : (p.cols - 1) * s;
    topLeft_m = dvec2(-r - b);
    layout.size_m = dvec2(lastX, (p.rows - 1) * s) + 2.0 * (r + b);
    layout.perRow = p.cols;
    layout.rows = p.rows;
    t.asymmetric = p.asymmetric;
    t.radiusSquared_cells = (r / s) * (r / s);
  }
  layout.rectangleCentre_m = dvec3(topLeft_m + 0.5 * layout.size_m, 0);
  // Rectangle (u, v) = (x / w + 1/2, y / h + 1/2) in its own frame, centred on the rectangle.
  auto uvOf = [&](dvec2 target_m) {
    return (target_m - dvec2(layout.rectangleCentre_m)) / layout.size_m + 0.5;
  };
  // The checkerboard's cell grid starts at the squares' corner, the circle grid's at the first dot.
  t.origin_uv = uvOf(kind == TextureKind::Checkerboard ? dvec2(-s) : dvec2(0));
  t.cell_uv = dvec2(s) / layout.size_m;

  for (int row = 0; row < layout.rows; ++row)
    for (int col = 0; col < layout.perRow; ++col) {
      TargetFeature f;
      f.row = row;
      f.col = col;
      const double x = kind == TextureKind::CircleGrid && p.asymmetric ? (2 * col + row % 2) * s : col * s;
      f.target_m = dvec3(x, row * s, 0);
      f.uv = uvOf(dvec2(f.target_m));
      layout.features.push_back(f);
    }
  return layout;
}

}  // namespace dicsynth
