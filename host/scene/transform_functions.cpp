// Transform values (4x4 homographies) and degrees().
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/warning.h"
#include "scene/constructors.h"
#include "scene/lua_sandbox.h"
#include "scene/lua_values.h"

namespace dicsynth::scene {

namespace {

/* ------------------------------------------------------------------------------------------------
Transforms: values of type Transform, a 4x4 homography acting on points p as M * (p, 1).

  Function                          | Meaning
  ----------------------------------+-------------------------------------------------------------
  translate(x, y, z), translate{x, y, z} | move by (x, y, z) metres
  rotate_x(a), rotate_y(a), rotate_z(a)  | rotate by a radians about the axis, right-handed:
                                    | rotate_y(a) maps (1, 0, 0) to (cos a, 0, -sin a)
  scale(s), scale(sx, sy, sz)       | scale about the origin; factors non-zero
  homography{m11, m12, m13, m14,    | any 4x4 matrix, 16 numbers written ROW by row as on paper
             m21, ..., m44}         | (the first four numbers are the first row)
  identity()                        | the identity
  A * B                             | composition: (A * B)(p) = A(B(p)), i.e. B first, then A
  degrees(d)                        | the number d * pi / 180 (angles are radians everywhere)

Example:  transform = translate(0, 0, 0.5) * rotate_y(degrees(35))  -- rotate, then move
------------------------------------------------------------------------------------------------ */

[[noreturn]] void fail(const char* function, const std::string& message) {
  throw ScriptError(std::string(function) + ": " + message);
}

double finiteNumber(lua_State* L, int index, const char* function, const std::string& what) {
  if (lua_type(L, index) != LUA_TNUMBER)
    fail(function, what + " must be a number, got " + typeName(L, index));
  const double x = lua_tonumber(L, index);
  if (!std::isfinite(x)) fail(function, what + " must be finite, got " + formatNumber(x));
  return x;
}

// The arguments as numbers: either `count` numbers, or (when tableOk) one table of them.
std::vector<double> numberArguments(lua_State* L, const char* function, std::size_t count,
                                    bool tableOk, const char* usage) {
  const int arguments = lua_gettop(L);
  std::vector<double> values;
  if (tableOk && arguments == 1 && lua_istable(L, 1)) {
    const lua_Unsigned length = lua_rawlen(L, 1);
    if (length != count)
      fail(function, "expected " + std::string(usage) + ", got a table of " +
                         std::to_string(length) + " values");
    for (std::size_t i = 1; i <= count; ++i) {
      lua_rawgeti(L, 1, static_cast<lua_Integer>(i));
      values.push_back(finiteNumber(L, -1, function, "value [" + std::to_string(i) + "]"));
      lua_pop(L, 1);
    }
    return values;
  }
  if (static_cast<std::size_t>(arguments) != count)
    fail(function, "expected " + std::string(usage) + ", got " + std::to_string(arguments) +
                       (arguments == 1 ? " argument" : " arguments"));
  for (int i = 1; i <= arguments; ++i)
    values.push_back(finiteNumber(L, i, function, "argument " + std::to_string(i)));
  return values;
}

void pushTransform(lua_State* L, const dmat4& matrix) { pushUserdata(L, TransformValue{matrix}); }

int translate(lua_State* L) {
  auto t = numberArguments(L, "translate", 3, true, "translate(x, y, z) or translate{x, y, z}");
  pushTransform(L, glm::translate(dmat4(1.0), dvec3(t[0], t[1], t[2])));
  return 1;
}

// Right-handed rotation by `angle` about coordinate axis `axis` (0 = x, 1 = y, 2 = z).
template <int Axis>
int rotate(lua_State* L) {
  static const char* const kNames[] = {"rotate_x", "rotate_y", "rotate_z"};
  const double angle = numberArguments(L, kNames[Axis], 1, false, "one angle in radians")[0];
  // More than a turn is nearly always degrees typed as radians: rotate_y(30) turned a plate 30 rad
  // = 1718.87°, nearly edge-on, without a word (the docs walk of 2026-11-29). Said, not refused: a
  // spin over many frames (rotate_z(frame * degrees(10))) passes a turn legitimately, and
  // math.fmod(a, 2 * math.pi) keeps it quiet.
  if (std::abs(angle) > 2 * kPi) {
    const LuaSandbox& sandbox = LuaSandbox::of(L);
    char degreesText[32];
    std::snprintf(degreesText, sizeof degreesText, "%.6g", angle * 180 / kPi);
    if (!sandbox.quiet())
      warnAtMost("angle beyond a turn", 3,
                 sandbox.here(L).str() + ": " + kNames[Axis] + "(" + formatNumber(angle) + "): " + formatNumber(angle) +
                     " rad is " + std::string(degreesText) + " degrees, more than a turn: " + kNames[Axis] +
                     "(degrees(" + formatNumber(angle) + ")) for " + formatNumber(angle) +
                     " degrees? (angles are radians; a spin past a turn on purpose: math.fmod(angle, 2 * math.pi) "
                     "says so)",
                 " (further such angles are not reported)");
  }
  const double c = std::cos(angle), s = std::sin(angle);
  const int i = (Axis + 1) % 3, j = (Axis + 2) % 3;  // the rotated plane, in right-handed order
  dmat4 m(1.0);  // m[col][row]: e_i → c e_i + s e_j, e_j → -s e_i + c e_j
  m[i][i] = c;
  m[i][j] = s;
  m[j][i] = -s;
  m[j][j] = c;
  pushTransform(L, m);
  return 1;
}

int scale(lua_State* L) {
  const std::vector<double> factors =
      lua_gettop(L) == 1 ? numberArguments(L, "scale", 1, false, "scale(s) or scale(sx, sy, sz)")
                         : numberArguments(L, "scale", 3, false, "scale(s) or scale(sx, sy, sz)");
  for (double f : factors)
    if (f == 0) fail("scale", "factors must be non-zero, got 0");
  const dvec3 s =
      factors.size() == 1 ? dvec3(factors[0]) : dvec3(factors[0], factors[1], factors[2]);
  pushTransform(L, glm::scale(dmat4(1.0), s));
  return 1;
}

int homography(lua_State* L) {
  auto v = numberArguments(L, "homography", 16, true, "homography{16 numbers}, written row by row");
  dmat4 m(1.0);
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) m[col][row] = v[4 * row + col];  // GLM: m[col][row]
  pushTransform(L, m);
  return 1;
}

int identity(lua_State* L) {
  numberArguments(L, "identity", 0, false, "no arguments");
  pushTransform(L, dmat4(1.0));
  return 1;
}

int degrees(lua_State* L) {
  const double d = numberArguments(L, "degrees", 1, false, "one angle in degrees")[0];
  lua_pushnumber(L, d * kPi / 180.0);
  return 1;
}

// A * B: B applied first.
int multiply(lua_State* L) {
  const TransformValue* a = toUserdata<TransformValue>(L, 1);
  const TransformValue* b = toUserdata<TransformValue>(L, 2);
  if (!a || !b)
    throw ScriptError("'*' composes two transforms, got " + typeName(L, 1) + " * " +
                      typeName(L, 2));
  const dmat4 product = a->matrix * b->matrix;
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(product[col][row]))
        throw ScriptError("transform product is not finite (overflow)");
  pushTransform(L, product);
  return 1;
}

int transformToString(lua_State* L) {
  const TransformValue* t = toUserdata<TransformValue>(L, 1);
  if (!t) return 0;
  std::string text = "Transform{";
  for (int row = 0; row < 4; ++row) {
    text += row ? ", {" : "{";
    for (int col = 0; col < 4; ++col) text += (col ? ", " : "") + formatNumber(t->matrix[col][row]);
    text += "}";
  }
  text += "}";
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

}  // namespace

void registerTransformFunctions(lua_State* L) {
  registerUserdataType<TransformValue>(
      L, {{"__mul", &protectedCall<multiply>}, {"__tostring", &protectedCall<transformToString>}});
  const luaL_Reg functions[] = {
      {"translate", &protectedCall<translate>}, {"rotate_x", &protectedCall<rotate<0>>},
      {"rotate_y", &protectedCall<rotate<1>>},  {"rotate_z", &protectedCall<rotate<2>>},
      {"scale", &protectedCall<scale>},         {"homography", &protectedCall<homography>},
      {"identity", &protectedCall<identity>},   {"degrees", &protectedCall<degrees>},
  };
  for (const luaL_Reg& function : functions) {
    lua_pushcfunction(L, function.func);
    lua_setglobal(L, function.name);
  }
}

}  // namespace dicsynth::scene
