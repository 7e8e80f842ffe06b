#pragma once
// Scene values as Lua sees them, and the reading of constructor parameter tables.
//
// Every value a constructor returns is a full userdata holding a C++ value (placement new; __gc
// runs its destructor) whose metatable is private (__metatable hides it), so a scene can pass the
// value around but cannot change what was validated. The metatable's __name ("Shape", "Camera",
// ...) is what error messages call the type.
//
// C functions written in C++ are registered through protectedCall<Body>: Body reports problems by
// throwing ScriptError, which becomes a Lua error "<scene>:LINE: message" at the calling line once
// every C++ object is destroyed (see the error-safety note in lua_sandbox.h).
#include <initializer_list>
#include <lua.hpp>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/math.h"
#include "scene/lua_sandbox.h"
#include "scene/scene.h"

namespace dicsynth {
class MeshField;  // io/mesh_field.h
}

namespace dicsynth::scene {

// A problem in the scene found by a C function; the message has no position (added on raise).
class ScriptError : public std::runtime_error {
 public:
  explicit ScriptError(const std::string& message) : std::runtime_error(message) {}
};

// The value of translate(), rotate_y(), ... and of their products: a 4x4 homography.
struct TransformValue {
  dmat4 matrix{1.0};
};

// The value of Rig.Stereo (rig_constructors.cpp): its two cameras, posed by the rig. The userdata
// also holds Lua values (user values, indices below): the posed cameras as Camera values, which
// rig.left / rig.right return (the same value each time), and the cameras the scene passed in, so
// that collectGlobals can tell when one of them is also a global.
struct StereoRigValue {
  SourceLoc where;
  Camera left, right;
};
enum RigUserValue : int {
  kRigPosedLeft = 1,
  kRigPosedRight = 2,
  kRigGivenLeft = 3,
  kRigGivenRight = 4,
  kRigUserValueCount = 4
};

// The value of Field.load (deform_constructors.cpp): a displacement field on a finite-element mesh.
struct FieldValue {
  SourceLoc where;
  std::shared_ptr<const MeshField> mesh;
};

// The type name of each userdata kind, as error messages and tostring() show it.
template <class T>
inline constexpr const char* kUserdataName = nullptr;
template <>
inline constexpr const char* kUserdataName<Camera> = "Camera";
template <>
inline constexpr const char* kUserdataName<Distortion> = "Distortion";
template <>
inline constexpr const char* kUserdataName<Shape> = "Shape";
template <>
inline constexpr const char* kUserdataName<Shader> = "Shader";
template <>
inline constexpr const char* kUserdataName<Texture> = "Texture";
template <>
inline constexpr const char* kUserdataName<Object> = "Object";
template <>
inline constexpr const char* kUserdataName<Light> = "Light";
template <>
inline constexpr const char* kUserdataName<TransformValue> = "Transform";
template <>
inline constexpr const char* kUserdataName<StereoRigValue> = "Rig";
template <>
inline constexpr const char* kUserdataName<FieldValue> = "Field";

// The metatable of T lives in the registry under the address of this variable: lookups by a light
// userdata key allocate nothing, so they cannot raise a Lua error.
template <class T>
inline const char kMetatableKey = 0;

// Runs body(L) as the body of a Lua C function: returns its result count, or -1 after pushing the
// error message "<scene>:LINE: what()" when it threw. Allocation is never refused meanwhile.
int runProtected(lua_State* L, int (*body)(lua_State*));

template <int (*Body)(lua_State*)>
int protectedCall(lua_State* L) {
  const int results = runProtected(L, Body);  // no C++ object of ours is alive after this line
  return results >= 0 ? results : lua_error(L);
}

template <class T>
int destroyUserdata(lua_State* L) {
  static_cast<T*>(lua_touserdata(L, 1))->~T();
  return 0;
}

// Creates T's metatable (__name, __gc, __metatable, plus `methods`) in the registry.
template <class T>
void registerUserdataType(lua_State* L, std::initializer_list<luaL_Reg> methods) {
  static_assert(alignof(T) <= alignof(lua_Number) && alignof(T) <= alignof(void*),
                "Lua aligns userdata memory for a double or a pointer, not more");
  lua_newtable(L);
  lua_pushstring(L, kUserdataName<T>);
  lua_setfield(L, -2, "__name");
  lua_pushstring(L, kUserdataName<T>);
  lua_setfield(L, -2, "__metatable");
  lua_pushcfunction(L, &destroyUserdata<T>);
  lua_setfield(L, -2, "__gc");
  for (const luaL_Reg& method : methods) {
    lua_pushcfunction(L, method.func);
    lua_setfield(L, -2, method.name);
  }
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kMetatableKey<T>);
}

// Pushes a new userdata holding `value` (and `userValues` Lua user values, nil until set). The
// metatable (hence __gc) is set once it is constructed.
template <class T>
void pushUserdata(lua_State* L, T value, int userValues = 0) {
  void* memory = lua_newuserdatauv(L, sizeof(T), userValues);
  new (memory) T(std::move(value));
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kMetatableKey<T>);
  lua_setmetatable(L, -2);
}

// The T held by the value at `index`, or nullptr when it is something else.
template <class T>
T* toUserdata(lua_State* L, int index) {
  void* memory = lua_touserdata(L, index);
  if (memory == nullptr || !lua_getmetatable(L, index)) return nullptr;
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kMetatableKey<T>);
  const bool isT = lua_rawequal(L, -1, -2);
  lua_pop(L, 2);
  return isT ? static_cast<T*>(memory) : nullptr;
}

// Sets global `name` to a table of constructors, e.g. Shape = { Sphere = ..., Box = ... }.
void setConstructorTable(lua_State* L, const char* name, std::initializer_list<luaL_Reg> functions);
// The same from a list built at run time (one constructor per kind of a registry).
void setConstructorTable(lua_State* L, const char* name, const std::vector<luaL_Reg>& functions);

// The type of a value as messages name it: "Shape" for our userdata, else Lua's type name.
std::string typeName(lua_State* L, int index);

// Reads the single parameter table of a constructor such as Shape.Sphere { radius = 0.1 }.
// Access is raw (no metamethods run). Every accessor validates type and finiteness and throws
// ScriptError("Shape.Sphere: 'radius' must be a number, got string") when the value is wrong.
class Params {
 public:
  // Checks that the arguments are one table (or nothing) whose keys are all in `keys`.
  Params(lua_State* L, std::string constructor, const std::vector<const char*>& keys);

  const std::string& constructor() const { return constructor_; }
  bool has(const char* key) const;
  int luaType(const char* key) const;  // LUA_TNIL, LUA_TNUMBER, ... of the raw value

  std::optional<double> number(const char* key) const;
  double number(const char* key, double fallback) const { return number(key).value_or(fallback); }
  double requiredNumber(const char* key) const;
  std::optional<long long> integer(const char* key) const;
  std::optional<std::string> string(const char* key) const;
  std::optional<bool> boolean(const char* key) const;  // true or false, nothing else
  // A table of count numbers (minCount..maxCount, maxCount may be kAnyCount), e.g. "{x, y, z}".
  static constexpr std::size_t kAnyCount = static_cast<std::size_t>(-1);
  std::optional<std::vector<double>> numbers(const char* key, std::size_t minCount,
                                             std::size_t maxCount, const char* shape) const;
  std::optional<dvec2> vec2(const char* key, const char* shape = "{x, y}") const;
  std::optional<dvec3> vec3(const char* key, const char* shape = "{x, y, z}") const;
  // A table of `count` tables of `size` numbers each, e.g. vertices = {{x,y,z}, ...}.
  std::optional<std::vector<std::vector<double>>> tables(const char* key, std::size_t count,
                                                         std::size_t size, const char* shape) const;
  // A table of exactly `count` {x, y, z} tables, e.g. controlPoints; `count` is described for
  // messages by countText ("countU × countV = 4 × 5 = 20"). One pass, no per-point table copies.
  std::optional<std::vector<dvec3>> vec3List(const char* key, std::size_t count,
                                             const std::string& countText) const;
  // A colour: one gray number or {r, g, b}.
  std::optional<dvec3> color(const char* key) const;
  // A number in [lo, hi] (`range` says so in messages), or the Rec. 709 luminance of {r, g, b}
  // with each component there; `fallback` when absent.
  double gray(const char* key, double fallback, double lo, double hi, const char* range) const;
  // Userdata of type T; `expected` names it for messages, e.g. "a Shader (Shader.Constant, ...)".
  template <class T>
  const T* userdata(const char* key, const char* expected) const {
    Pushed value(L_, key);
    if (value.isNil()) return nullptr;
    const T* held = toUserdata<T>(L_, -1);
    if (held == nullptr) fail(quote(key) + " must be " + expected + ", got " + typeName(L_, -1));
    return held;
  }

  // Throws ScriptError("<constructor>: message").
  [[noreturn]] void fail(const std::string& message) const;
  // Range check helper: fails with "'key' must be <condition>, got <value>" unless ok.
  void require(bool ok, const char* key, const char* condition, double value) const;
  // The same for an angle in radians; a value beyond 2π (degrees meant: `tilt = 30`) adds
  // "; angles are in radians: degrees(30) for 30 degrees".
  void requireAngle(bool ok, const char* key, const char* condition, double value_rad) const;

  static std::string quote(const char* key) { return std::string("'") + key + "'"; }

 private:
  // Pushes t[key] (raw) for the lifetime of the object.
  class Pushed {
   public:
    Pushed(lua_State* L, const char* key);
    ~Pushed() { lua_pop(L_, 1); }
    Pushed(const Pushed&) = delete;
    Pushed& operator=(const Pushed&) = delete;
    bool isNil() const { return lua_isnil(L_, -1); }

   private:
    lua_State* L_;
  };

  double checkNumber(int index, const std::string& what) const;
  // Reads a plain {x, y, z} of finite numbers at stack `index` (absolute); false if it is not one.
  bool readVec3(int index, dvec3& out) const;
  // Numbers of the sequence at stack `index` (absolute), minCount..maxCount of them.
  std::vector<double> checkNumbers(int index, const std::string& what, std::size_t minCount,
                                   std::size_t maxCount, const char* shape) const;

  lua_State* L_;
  std::string constructor_;
};

}  // namespace dicsynth::scene
