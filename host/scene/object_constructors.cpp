// Texture.Constant, Texture.File, Object.Simple (Shader.* and Light.*: shading_constructors.cpp).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "scene/constructors.h"
#include "scene/lua_values.h"

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

  Parameter | Value   | Default  | Meaning
  ----------+---------+----------+-------------------------------------------------------------
  fileName  | string  | required | image file; a relative path is relative to the scene file's
            |         |          | folder, not to the working directory

The file must exist and be readable when the constructor runs (the error names the line); it is
decoded later, when the scene is prepared.

Example:  Texture.File { fileName = "speckle.tif" }
------------------------------------------------------------------------------------------------ */
int textureFile(lua_State* L) {
  Params p(L, "Texture.File", {"fileName"});
  const LuaSandbox& sandbox = LuaSandbox::of(L);
  Texture texture;
  texture.kind = TextureKind::File;
  texture.where = sandbox.here(L);
  const std::optional<std::string> fileName = p.string("fileName");
  if (!fileName) p.fail("missing required 'fileName'");
  if (fileName->empty()) p.fail("'fileName' must not be empty");

  // Resolve against the scene's folder, then check the file can be read.
  const std::filesystem::path given(*fileName);
  const std::filesystem::path resolved = given.is_absolute() ? given : sandbox.sceneDir() / given;
  texture.path = resolved.string();
  std::string name = "'" + *fileName + "'";
  if (texture.path != *fileName) name += " (resolved to '" + texture.path + "')";
  std::error_code ec;
  if (std::filesystem::is_directory(resolved, ec))
    p.fail("cannot read " + name + ": it is a folder");
  std::FILE* file = std::fopen(texture.path.c_str(), "rb");
  if (file == nullptr) p.fail("cannot read " + name + ": " + std::strerror(errno));
  std::fclose(file);
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
  const Shape* shape = p.userdata<Shape>(
      "shape",
      "a Shape (Shape.Sphere, Shape.Box, Shape.Rectangle, Shape.Plane, Shape.Triangle, "
      "Shape.Nurbs, Nurbs.plate, Nurbs.cylinderSegment, Nurbs.dogbone)");
  if (!shape) p.fail("missing required 'shape'");
  object.shape = *shape;
  if (const Shader* shader =
          p.userdata<Shader>("shader", kShaderExpected)) {
    object.shader = *shader;
  } else {
    object.shader.where = object.where;
  }
  if (const Texture* texture =
          p.userdata<Texture>("texture", "a Texture (Texture.Constant, Texture.File)")) {
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
  lua_pushstring(
      L, texture && texture->kind == TextureKind::File ? "Texture.File" : "Texture.Constant");
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
      {{"Constant", &protectedCall<textureConstant>}, {"File", &protectedCall<textureFile>}});
  setConstructorTable(L, "Object", {{"Simple", &protectedCall<objectSimple>}});
}

}  // namespace dicsynth::scene
