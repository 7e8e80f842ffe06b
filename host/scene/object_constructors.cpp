// Texture.Constant, Texture.File, Texture.Speckle, Object.Simple (Shader.* and Light.*:
// shading_constructors.cpp).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "shapes/registry.h"

namespace dicsynth::scene {

namespace {

/* ------------------------------------------------------------------------------------------------
Texture.Constant: the same value everywhere.

  Parameter | Value   | Default | Meaning
  ----------+---------+---------+--------------------------------------
  value     | number  | 1       | >= 0, multiplies the shader's colour

Example:  Texture.Constant { value = 0.5 }
------------------------------------------------------------------------------------------------ */
int textureConstant(lua_State* L) {
  Params p(L, "Texture.Constant", {"value"});
  Texture texture;
  texture.kind = TextureKind::Constant;
  texture.where = LuaSandbox::of(L).here(L);
  texture.value = p.number("value", 1.0);
  p.require(texture.value >= 0, "value", ">= 0", texture.value);
  pushUserdata(L, std::move(texture));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Texture.File: an image (e.g. a speckle pattern) glued on the surface's (u, v) parameters.

  Parameter     | Value   | Default  | Meaning
  --------------+---------+----------+---------------------------------------------------------
  fileName      | string  | required | image file; a relative path is relative to the scene
                |         |          | file's folder, not to the working directory
  interpolation | string  | "cubic"  | "cubic": interpolating cubic B-spline (4×4 texels);
                |         |          | "quintic": interpolating quintic B-spline (6×6 texels),
                |         |          | less interpolation bias (texture/bspline.h, README)

The file must exist and be readable when the constructor runs (the error names the line); it is
decoded later, when the scene is prepared.

Example:  Texture.File { fileName = "speckle.tif"; interpolation = "quintic" }
------------------------------------------------------------------------------------------------ */
int textureFile(lua_State* L) {
  Params p(L, "Texture.File", {"fileName", "interpolation"});
  const LuaSandbox& sandbox = LuaSandbox::of(L);
  Texture texture;
  texture.kind = TextureKind::File;
  texture.where = sandbox.here(L);
  const std::optional<std::string> fileName = p.string("fileName");
  if (!fileName) p.fail("missing required 'fileName'");
  if (fileName->empty()) p.fail("'fileName' must not be empty");
  const std::string interpolation = p.string("interpolation").value_or("cubic");
  if (interpolation == "cubic")
    texture.interpolation = Interpolation::Cubic;
  else if (interpolation == "quintic")
    texture.interpolation = Interpolation::Quintic;
  else
    p.fail("'interpolation' must be \"cubic\" or \"quintic\", got \"" + interpolation + "\"");

  // Resolve against the scene's folder, then check the file can be read.
  const std::filesystem::path given(*fileName);
  const std::filesystem::path resolved = given.is_absolute() ? given : sandbox.sceneDir() / given;
  texture.path = resolved.string();
  std::string name = "'" + *fileName + "'";
  if (texture.path != *fileName) name += " (resolved to '" + texture.path + "')";
  std::error_code ec;
  if (std::filesystem::is_directory(resolved, ec))
    p.fail("cannot read " + name + ": it is a folder");
  if (std::filesystem::exists(resolved, ec) && !std::filesystem::is_regular_file(resolved, ec))
    p.fail("cannot read " + name + ": not a regular file");
  std::FILE* file = std::fopen(texture.path.c_str(), "rb");
  if (file == nullptr) p.fail("cannot read " + name + ": " + std::strerror(errno));
  std::fclose(file);
  pushUserdata(L, std::move(texture));
  return 1;
}

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

Example:  Texture.Speckle { radius = 0.004; density = 0.5; aspect = 0.5; seed = 7 }
------------------------------------------------------------------------------------------------ */
int textureSpeckle(lua_State* L) {
  Params p(L, "Texture.Speckle", {"radius", "density", "aspect", "seed", "dark", "light"});
  Texture texture;
  texture.kind = TextureKind::Speckle;
  texture.where = LuaSandbox::of(L).here(L);
  const long long seed = p.integer("seed").value_or(1);
  p.require(seed >= 0 && seed <= 0xffffffffLL, "seed", "an integer in 0 .. 2^32 - 1", double(seed));
  try {
    texture.speckle = makeAnalyticSpeckle(p.number("radius", 0.005), p.number("density", 0.5),
                                          p.number("aspect", 1.0), std::uint32_t(seed), p.number("dark", 0.0),
                                          p.number("light", 1.0));
  } catch (const InputError& e) {
    p.fail(e.what());
  }
  pushUserdata(L, std::move(texture));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Object.Simple: a shape with a shader and a texture, placed by a transform. Only objects assigned
to global variables are rendered (the variable name names the object; objectId follows the sorted
names).

  Parameter | Value      | Default                 | Meaning
  ----------+------------+-------------------------+-----------------------------------------------
  shape     | Shape      | required                | Shape.Sphere { ... }, Shape.Box { ... }, ...
  shader    | Shader     | Shader.Constant {}      | white
  texture   | Texture    | Texture.Constant {}     | value 1
  transform | Transform  | identity()              | any invertible homography, applied to the shape
            |            |                         | about its location:
            |            |                         | worldFromShape = translate(location) *
transform

Example:
  plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.1}; location = {0, 0, 0.5} };
                          shader = Shader.Lambert {}; texture = Texture.File { fileName = "s.tif" };
                          transform = rotate_y(degrees(35)) }
------------------------------------------------------------------------------------------------ */
int objectSimple(lua_State* L) {
  Params p(L, "Object.Simple", {"shape", "shader", "texture", "transform"});
  Object object;
  object.where = LuaSandbox::of(L).here(L);
  static const std::string kShapeExpected = [] {
    std::string text = "a Shape (";
    for (const shapes::ShapeKindInfo& k : shapes::kShapeKinds) text += std::string("Shape.") + k.name + ", ";
    return text + "Nurbs.plate, Nurbs.cylinderSegment, Nurbs.dogbone)";  // the specimens (nurbs_constructors.cpp)
  }();
  const Shape* shape = p.userdata<Shape>("shape", kShapeExpected.c_str());
  if (!shape) p.fail("missing required 'shape'");
  object.shape = *shape;
  if (const Shader* shader =
          p.userdata<Shader>("shader", shaderExpected())) {
    object.shader = *shader;
  } else {
    object.shader.where = object.where;
  }
  if (const Texture* texture =
          p.userdata<Texture>("texture", "a Texture (Texture.Constant, Texture.File, Texture.Speckle)")) {
    object.texture = *texture;
  } else {
    object.texture.where = object.where;
  }
  if (const TransformValue* transform = p.userdata<TransformValue>(
          "transform", "a Transform (translate, rotate_x, ..., homography)"))
    object.transform = transform->matrix;

  // The transform must be invertible, relative to its own scale (Frobenius norm⁴).
  double normSquared = 0;
  bool finite = true;
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      finite = finite && std::isfinite(object.transform[col][row]);
      normSquared += object.transform[col][row] * object.transform[col][row];
    }
  if (!finite) p.fail("'transform' must be finite");
  const double det = glm::determinant(object.transform);
  if (!(std::fabs(det) > 1e-12 * normSquared * normSquared))
    p.fail("'transform' must be invertible, but its determinant is " + formatNumber(det));
  pushUserdata(L, std::move(object));
  return 1;
}

int textureToString(lua_State* L) {
  const Texture* texture = toUserdata<Texture>(L, 1);
  lua_pushstring(L, texture && texture->kind == TextureKind::File      ? "Texture.File"
                    : texture && texture->kind == TextureKind::Speckle ? "Texture.Speckle"
                                                                       : "Texture.Constant");
  return 1;
}

int objectToString(lua_State* L) {
  const Object* object = toUserdata<Object>(L, 1);
  const TextureKind kind = object ? object->texture.kind : TextureKind::Constant;
  lua_pushstring(L, kind == TextureKind::Checkerboard ? "Target.Checkerboard"
                    : kind == TextureKind::CircleGrid ? "Target.CircleGrid"
                                                      : "Object.Simple");
  return 1;
}

}  // namespace

void registerObjectConstructors(lua_State* L) {
  registerUserdataType<Texture>(L, {{"__tostring", &textureToString}});
  registerUserdataType<Object>(L, {{"__tostring", &objectToString}});
  setConstructorTable(
      L, "Texture",
      {{"Constant", &protectedCall<textureConstant>},
       {"File", &protectedCall<textureFile>},
       {"Speckle", &protectedCall<textureSpeckle>}});
  setConstructorTable(L, "Object", {{"Simple", &protectedCall<objectSimple>}});
}

}  // namespace dicsynth::scene
