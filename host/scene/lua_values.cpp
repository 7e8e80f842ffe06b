// Userdata helpers and the constructor parameter reader (see lua_values.h).
#include "scene/lua_values.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/closest_name.h"
#include "core/math.h"

namespace dicsynth::scene {

namespace {

// Number of entries of the table at `index`, and whether they are exactly [1..n].
struct TableShape {
  std::size_t entries = 0;
  bool isSequence = true;
};

TableShape shapeOf(lua_State* L, int index) {
  TableShape shape;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    lua_pop(L, 1);
    ++shape.entries;
  }
  for (std::size_t i = 1; i <= shape.entries; ++i) {
    if (lua_rawgeti(L, index, static_cast<lua_Integer>(i)) == LUA_TNIL) shape.isSequence = false;
    lua_pop(L, 1);
  }
  return shape;
}

}  // namespace

int runProtected(lua_State* L, int (*body)(lua_State*)) {
  LuaSandbox::UnlimitedScope unlimited(L);
  std::string message;
  try {
    return body(L);
  } catch (const ScriptError& e) {
    message = e.what();
  } catch (const std::bad_alloc&) {
    message = "out of memory";
  } catch (const std::exception& e) {
    message = std::string("internal error: ") + e.what();
  }
  lua_pushfstring(L, "%s:%d: ", kChunkToken, LuaSandbox::currentLine(L));
  lua_pushlstring(L, message.data(), message.size());
  lua_concat(L, 2);
  return -1;
}

void setConstructorTable(lua_State* L, const char* name,
                         std::initializer_list<luaL_Reg> functions) {
  setConstructorTable(L, name, std::vector<luaL_Reg>(functions));
}

namespace {

// A constructor table's __index (upvalue 1: the table's name): a name it does not hold is a typo.
// `Texture.Speckel { ... }` said Lua's "attempt to call a nil value (field 'Speckel')" (the docs
// walk of 2026-11-29), where a key's typo gets "did you mean".
int missingConstructor(lua_State* L) {
  const std::string table = lua_tostring(L, lua_upvalueindex(1));
  // Only a string key is named: converting another could run a __tostring, which may raise.
  const std::string key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "[" + typeName(L, 2) + "]";
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, 1) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING) names.emplace_back(lua_tostring(L, -2));
    lua_pop(L, 1);
  }
  std::sort(names.begin(), names.end());
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + table + "." + n;
  const std::optional<std::string> near = closestName(key, names);
  throw ScriptError(table + "." + key + ": no such constructor" + (near ? " (did you mean " + table + "." + *near + "?)" : "") +
                    "; " + table + " has " + list);
}

}  // namespace

void setConstructorTable(lua_State* L, const char* name, const std::vector<luaL_Reg>& functions) {
  lua_createtable(L, 0, static_cast<int>(functions.size()));
  for (const luaL_Reg& function : functions) {
    lua_pushcfunction(L, function.func);
    lua_setfield(L, -2, function.name);
  }
  lua_createtable(L, 0, 2);  // its metatable
  lua_pushstring(L, name);
  lua_pushcclosure(L, &protectedCall<missingConstructor>, 1);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");  // the scene cannot replace or inspect it
  lua_setmetatable(L, -2);
  lua_setglobal(L, name);
}

std::string typeName(lua_State* L, int index) {
  if (lua_type(L, index) == LUA_TUSERDATA && lua_getmetatable(L, index)) {
    lua_pushliteral(L, "__name");
    lua_rawget(L, -2);
    std::string name = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "userdata";
    lua_pop(L, 2);
    return name;
  }
  return lua_typename(L, lua_type(L, index));
}

Params::Pushed::Pushed(lua_State* L, const char* key) : L_(L) {
  lua_pushstring(L, key);
  lua_rawget(L, 1);
}

Params::Params(lua_State* L, std::string constructor, const std::vector<const char*>& keys)
    : L_(L), constructor_(std::move(constructor)) {
  std::string validKeys;
  for (const char* key : keys) validKeys += (validKeys.empty() ? "" : ", ") + std::string(key);
  // What the messages below end with: the keys, or that there are none (not an empty list).
  const std::string keysText = keys.size() == 0 ? constructor_ + " takes no parameters" : "valid keys: " + validKeys;

  // One table argument; none (Shape.Sphere()) reads as an empty table.
  const int arguments = lua_gettop(L);
  if (arguments > 1)
    fail("expected one table of parameters { key = value; ... }, got " + std::to_string(arguments) +
         " arguments");
  if (arguments == 0 || lua_isnil(L, 1)) {
    lua_settop(L, 0);
    lua_newtable(L);
  } else if (!lua_istable(L, 1)) {
    fail("expected a table of parameters { key = value; ... }, got " + typeName(L, 1));
  }

  // Every key must be one of `keys`: a typo is an error, not a silently ignored parameter.
  std::vector<std::string> unknown;
  lua_pushnil(L);
  while (lua_next(L, 1) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) {
      const std::string where = lua_type(L, -1) == LUA_TNUMBER
                                    ? "[" + formatNumber(lua_tonumber(L, -1)) + "]"
                                    : "a " + typeName(L, -1) + " key";
      fail("parameters must be named (key = value), got a value at " + where + "; " + keysText);
    }
    std::string key = lua_tostring(L, -1);
    if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; }))
      unknown.push_back(std::move(key));
  }
  if (unknown.empty()) return;

  std::sort(unknown.begin(), unknown.end());
  std::string message = unknown.size() == 1 ? "unknown key " : "unknown keys ";
  // A key is shown up to 64 bytes: a scene's 10 MB key made a 10 MB message line.
  const auto shown = [](const std::string& key) {
    return key.size() <= 64 ? key : key.substr(0, 48) + "... (" + std::to_string(key.size()) + " bytes)";
  };
  for (std::size_t i = 0; i < unknown.size(); ++i) message += (i ? ", '" : "'") + shown(unknown[i]) + "'";
  // Suggest the closest valid key for a single typo.
  if (unknown.size() == 1)
    if (const auto best = closestName(unknown[0], std::vector<std::string>(keys.begin(), keys.end())))
      message += " (did you mean '" + *best + "'?)";
  fail(message + "; " + keysText);
}

void Params::fail(const std::string& message) const {
  throw ScriptError(constructor_ + ": " + message);
}

void Params::require(bool ok, const char* key, const char* condition, double value) const {
  if (!ok) fail(quote(key) + " must be " + condition + ", got " + formatNumber(value));
}

void Params::requireAngle(bool ok, const char* key, const char* condition, double value_rad) const {
  if (ok) return;
  std::string message = quote(key) + " must be " + condition + ", got " + formatNumber(value_rad);
  if (std::abs(value_rad) > 2 * kPi)
    message += "; angles are in radians: degrees(" + formatNumber(value_rad) + ") for " + formatNumber(value_rad) + " degrees";
  fail(message);
}

bool Params::has(const char* key) const {
  Pushed value(L_, key);
  return !value.isNil();
}

int Params::luaType(const char* key) const {
  Pushed value(L_, key);
  return lua_type(L_, -1);
}

double Params::checkNumber(int index, const std::string& what) const {
  if (lua_type(L_, index) != LUA_TNUMBER)
    fail(what + " must be a number, got " + typeName(L_, index));
  const double x = lua_tonumber(L_, index);
  if (!std::isfinite(x)) fail(what + " must be finite, got " + formatNumber(x));
  return x;
}

std::vector<double> Params::checkNumbers(int index, const std::string& what, std::size_t minCount,
                                         std::size_t maxCount, const char* shape) const {
  std::string count = minCount == maxCount ? std::to_string(minCount) + " "
                      : maxCount != kAnyCount
                          ? std::to_string(minCount) + " to " + std::to_string(maxCount) + " "
                      : minCount > 0 ? "at least " + std::to_string(minCount) + " "
                                     : "";
  const std::string expected =
      what + " must be " + shape + " (" + count + (maxCount == 1 ? "number)" : "numbers)");
  if (!lua_istable(L_, index)) fail(expected + ", got " + typeName(L_, index));
  const TableShape table = shapeOf(L_, index);
  if (!table.isSequence) fail(expected + ", got a table with named or missing entries");
  if (table.entries < minCount || table.entries > maxCount)
    fail(expected + ", got " + std::to_string(table.entries) + " values");
  std::vector<double> values;
  for (std::size_t i = 1; i <= table.entries; ++i) {
    lua_rawgeti(L_, index, static_cast<lua_Integer>(i));
    values.push_back(checkNumber(lua_gettop(L_), what + "[" + std::to_string(i) + "]"));
    lua_pop(L_, 1);
  }
  return values;
}

std::optional<double> Params::number(const char* key) const {
  Pushed value(L_, key);
  if (value.isNil()) return std::nullopt;
  return checkNumber(-1, quote(key));
}

std::optional<bool> Params::boolean(const char* key) const {
  Pushed value(L_, key);
  if (value.isNil()) return std::nullopt;
  if (lua_type(L_, -1) != LUA_TBOOLEAN) fail(quote(key) + " must be true or false");
  return lua_toboolean(L_, -1) != 0;
}

double Params::requiredNumber(const char* key) const {
  std::optional<double> value = number(key);
  if (!value) fail("missing required " + quote(key));
  return *value;
}

std::optional<long long> Params::integer(const char* key) const {
  std::optional<double> value = number(key);
  if (!value) return std::nullopt;
  if (*value != std::floor(*value) || std::fabs(*value) > 9.0e15)
    fail(quote(key) + " must be an integer, got " + formatNumber(*value));
  return static_cast<long long>(*value);
}

std::optional<std::string> Params::string(const char* key) const {
  Pushed value(L_, key);
  if (value.isNil()) return std::nullopt;
  if (lua_type(L_, -1) != LUA_TSTRING)
    fail(quote(key) + " must be a string, got " + typeName(L_, -1));
  std::size_t length = 0;
  const char* text = lua_tolstring(L_, -1, &length);
  return std::string(text, length);
}

std::optional<std::vector<double>> Params::numbers(const char* key, std::size_t minCount,
                                                   std::size_t maxCount, const char* shape) const {
  Pushed value(L_, key);
  if (value.isNil()) return std::nullopt;
  return checkNumbers(lua_gettop(L_), quote(key), minCount, maxCount, shape);
}

std::optional<dvec2> Params::vec2(const char* key, const char* shape) const {
  auto values = numbers(key, 2, 2, shape);
  if (!values) return std::nullopt;
  return dvec2((*values)[0], (*values)[1]);
}

std::optional<dvec3> Params::vec3(const char* key, const char* shape) const {
  auto values = numbers(key, 3, 3, shape);
  if (!values) return std::nullopt;
  return dvec3((*values)[0], (*values)[1], (*values)[2]);
}

std::optional<std::vector<std::vector<double>>> Params::tables(const char* key, std::size_t count,
                                                               std::size_t size,
                                                               const char* shape) const {
  Pushed value(L_, key);
  if (value.isNil()) return std::nullopt;
  const int index = lua_gettop(L_);
  const std::string expected =
      quote(key) + " must be " + shape + " (" + std::to_string(count) + " tables)";
  if (!lua_istable(L_, index)) fail(expected + ", got " + typeName(L_, index));
  const TableShape table = shapeOf(L_, index);
  if (!table.isSequence) fail(expected + ", got a table with named or missing entries");
  if (table.entries != count) fail(expected + ", got " + std::to_string(table.entries) + " values");
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 1; i <= count; ++i) {
    lua_rawgeti(L_, index, static_cast<lua_Integer>(i));
    const std::string what = quote(key) + "[" + std::to_string(i) + "]";
    const std::string rowShape = size == 2 ? "{u, v}" : "{x, y, z}";
    rows.push_back(checkNumbers(lua_gettop(L_), what, size, size, rowShape.c_str()));
    lua_pop(L_, 1);
  }
  return rows;
}

bool Params::readVec3(int index, dvec3& out) const {
  if (!lua_istable(L_, index) || lua_rawlen(L_, index) != 3) return false;
  int entries = 0;
  lua_pushnil(L_);
  while (entries <= 3 && lua_next(L_, index) != 0) {
    lua_pop(L_, 1);
    ++entries;
  }
  if (entries > 3) lua_pop(L_, 1);  // the key lua_next left on the stack
  if (entries != 3) return false;
  for (int c = 0; c < 3; ++c) {
    const bool isNumber = lua_rawgeti(L_, index, c + 1) == LUA_TNUMBER;
    out[c] = isNumber ? lua_tonumber(L_, -1) : 0.0;
    lua_pop(L_, 1);
    if (!isNumber || !std::isfinite(out[c])) return false;
  }
  return true;
}

std::optional<std::vector<dvec3>> Params::vec3List(const char* key, std::size_t count,
                                                   const std::string& countText) const {
  Pushed value(L_, key);
  if (value.isNil()) return std::nullopt;
  const int index = lua_gettop(L_);
  const std::string expected =
      quote(key) + " must be {{x, y, z}, ...} (" + countText + " tables {x, y, z})";
  if (!lua_istable(L_, index)) fail(expected + ", got " + typeName(L_, index));
  const TableShape table = shapeOf(L_, index);
  if (!table.isSequence) fail(expected + ", got a table with named or missing entries");
  if (table.entries != count) fail(expected + ", got " + std::to_string(table.entries) + " values");
  std::vector<dvec3> points(count);
  for (std::size_t i = 1; i <= count; ++i) {
    lua_rawgeti(L_, index, static_cast<lua_Integer>(i));
    const int point = lua_gettop(L_);
    // The usual case, a plain {x, y, z} of finite numbers, is read without building messages;
    // anything else goes to checkNumbers, which throws the message for what is wrong.
    if (!readVec3(point, points[i - 1])) {
      checkNumbers(point, quote(key) + "[" + std::to_string(i) + "]", 3, 3, "{x, y, z}");
      DS_CHECK(false, "checkNumbers accepted a point that readVec3 refused");
    }
    lua_pop(L_, 1);
  }
  return points;
}

std::optional<dvec3> Params::color(const char* key) const {
  Pushed value(L_, key);
  if (value.isNil()) return std::nullopt;
  if (lua_type(L_, -1) == LUA_TNUMBER) return dvec3(checkNumber(-1, quote(key)));
  if (!lua_istable(L_, -1))
    fail(quote(key) + " must be a gray number or {r, g, b}, got " + typeName(L_, -1));
  std::vector<double> rgb = checkNumbers(lua_gettop(L_), quote(key), 3, 3, "{r, g, b}");
  return dvec3(rgb[0], rgb[1], rgb[2]);
}

double Params::gray(const char* key, double fallback, double lo, double hi, const char* range) const {
  double value = fallback;
  if (luaType(key) == LUA_TTABLE) {
    const dvec3 rgb = *color(key);
    for (double c : {rgb.x, rgb.y, rgb.z}) require(c >= lo && c <= hi, key, range, c);
    value = luminance(rgb);
  } else {
    value = number(key, fallback);
  }
  require(value >= lo && value <= hi, key, range, value);
  return value;
}

}  // namespace dicsynth::scene
