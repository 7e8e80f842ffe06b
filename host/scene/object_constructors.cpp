// Texture.<Kind> for the kinds of the texture registry (host/textures/registry.h: each kind's home
// documents and parses its parameters), Object.Simple (Shader.* and Light.*:
// shading_constructors.cpp; Target.*: target_constructors.cpp).
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "core/warning.h"
#include "geometry/homography.h"
#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "shapes/registry.h"
#include "textures/registry.h"

namespace dicsynth::scene {

namespace {

// Texture.<Kind> for every kind of the registry whose constructor is in the Texture table: the
// kind's home documents and parses its parameters (host/textures/<kind>.h).
template <class Kind>
int textureConstructor(lua_State* L) {
  const std::vector<const char*> keys(Kind::kKeys.begin(), Kind::kKeys.end());
  Params p(L, Kind::kConstructor, keys);
  const LuaSandbox& sandbox = LuaSandbox::of(L);
  Texture texture;
  texture.where = sandbox.here(L);
  texture.model = Kind::parse(p, sandbox.sceneDir());
  // A kind that changed a value it was given says so once, where the scene is first evaluated (a
  // periodic Texture.Speckle's radius rounded to whole cells).
  if constexpr (requires(const Kind& k) { k.loadNote(); })
    if (!sandbox.quiet())
      if (const std::string text = std::get<Kind>(texture.model).loadNote(); !text.empty())
        noteOnce(texture.where.str() + ": note: " + Kind::kConstructor + ": " + text);
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
// What a 'texture' parameter must be: the registry's Texture.* kinds, in number order.
const std::string& textureExpected() {
  static const std::string text = [] {
    std::string list;
    textures::forEachKind([&](auto kind) {
      using Kind = typename decltype(kind)::type;
      if constexpr (textures::isTextureConstructor<Kind>()) list += std::string(list.empty() ? "" : ", ") + Kind::kConstructor;
    });
    return "a Texture (" + list + ")";
  }();
  return text;
}

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
          p.userdata<Texture>("texture", textureExpected().c_str())) {
    object.texture = *texture;
  } else {
    object.texture.where = object.where;
  }
  if (const TransformValue* transform = p.userdata<TransformValue>(
          "transform", "a Transform (translate, rotate_x, ..., homography)"))
    object.transform = transform->matrix;

  bool finite = true;
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) finite = finite && std::isfinite(object.transform[col][row]);
  if (!finite) p.fail("'transform' must be finite");
  const double ratio = invertibilityRatio(object.transform);
  if (!(ratio > kMinInvertibilityRatio))
    p.fail("'transform' must be invertible, but its determinant is " + formatNumber(glm::determinant(object.transform)) +
           (ratio > 0 ? " (" + formatNumber(ratio) + " of its columns' lengths' product, translation taken out; at least " +
                            formatNumber(kMinInvertibilityRatio) + " is needed)"
                      : ""));
  pushUserdata(L, std::move(object));
  return 1;
}

int textureToString(lua_State* L) {
  const Texture* texture = toUserdata<Texture>(L, 1);
  lua_pushstring(L, texture ? textures::kindInfo(texture->model).constructor : "Texture");
  return 1;
}

// A target is an Object whose texture is a target's (its constructor's name); any other, Object.Simple.
int objectToString(lua_State* L) {
  const Object* object = toUserdata<Object>(L, 1);
  const bool target = object && textures::targetPattern(object->texture.model) != nullptr;
  lua_pushstring(L, target ? textures::kindInfo(object->texture.model).constructor : "Object.Simple");
  return 1;
}

}  // namespace

void registerObjectConstructors(lua_State* L) {
  registerUserdataType<Texture>(L, {{"__tostring", &textureToString}});
  registerUserdataType<Object>(L, {{"__tostring", &objectToString}});
  std::vector<luaL_Reg> constructors;
  textures::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    if constexpr (textures::isTextureConstructor<Kind>())
      constructors.push_back({Kind::kName, &protectedCall<textureConstructor<Kind>>});
  });
  setConstructorTable(L, "Texture", constructors);
  setConstructorTable(L, "Object", {{"Simple", &protectedCall<objectSimple>}});
}

}  // namespace dicsynth::scene
