// The scene functions that declare a sweep, and the reading of the global `sweep`.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "core/json.h"
#include "scene/constructors.h"
#include "scene/define_value.h"
#include "scene/lua_values.h"
#include "scene/sweep_declaration.h"

namespace dicsynth {

std::string SweepValue::defineText() const {
  switch (kind) {
    case Kind::Number: return defineNumberText(number);
    case Kind::Boolean: return boolean ? "true" : "false";
    case Kind::String: return text;
  }
  return text;
}

std::string SweepValue::json() const {
  switch (kind) {
    // −0 as "-0.0": JSON readers take "-0" for the integer 0 (Python's json does), losing the sign.
    case Kind::Number: return number == 0 && std::signbit(number) ? "-0.0" : json::number(number);
    case Kind::Boolean: return json::boolean(boolean);
    case Kind::String: return json::quote(text);
  }
  return json::quote(text);
}

namespace scene {
template <>
inline constexpr const char* kUserdataName<SweepDeclaration> = "Sweep";

namespace {

/* ------------------------------------------------------------------------------------------------
Sweep declarations (docs/sweeps.md). A scene declares its sweep by assigning the global `sweep`:

  Form                                           | Points
  -----------------------------------------------+------------------------------------------------
  sweep = { a = {v1, v2, ...}, b = v, ... }      | full grid: every combination; a single value is a
                                                 | one-value list. Index order: names sorted
                                                 | (byte order), the LAST name varies fastest
  sweep = points { {a = 1, b = 2}, {a = 3, b = 4} } | the listed points, in order; every point names
                                                 | the same parameters
  sweep = random { n = 1000, seed = 7,           | n points, parameter x uniform in [lo, hi) drawn
                   a = {lo, hi}, ... }           | by counter-based hashing of (seed, index, name)
                                                 | (seed: integer 0..2^32-1, default 1)
  linspace(a, b, n)                              | the table of n numbers a + i·(b − a)/(n − 1),
                                                 | i = 0..n-1, the last exactly b; n = 1 gives {a}

Values are numbers, booleans or strings (a string that reads as a number arrives as a number,
as with -D). The scene never sees the declaration's tables: each point sets its parameters as
globals, exactly like -D name=value, before the scene runs.
------------------------------------------------------------------------------------------------ */


[[noreturn]] void fail(const std::string& function, const std::string& message) {
  throw ScriptError(function + ": " + message);
}

SweepValue readValue(lua_State* L, int index, const std::string& function, const std::string& what) {
  SweepValue v;
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      v.number = lua_tonumber(L, index);
      if (!std::isfinite(v.number)) fail(function, what + " must be finite, got " + formatNumber(v.number));
      // Held as a double: an integer beyond 2^53 would reach the scene rounded (scene/define_value.h).
      if (lua_isinteger(L, index)) {
        const long long integer = lua_tointeger(L, index);
        if (const std::string problem = sweepNumberProblem({v.number, true, integer}); !problem.empty())
          fail(function, what + " = " + std::to_string(integer) + problem);
      }
      return v;
    case LUA_TBOOLEAN:
      v.kind = SweepValue::Kind::Boolean;
      v.boolean = lua_toboolean(L, index) != 0;
      return v;
    case LUA_TSTRING: {
      std::size_t length = 0;
      const char* s = lua_tolstring(L, index, &length);
      v.text.assign(s, length);
      // A string that reads as a number arrives as that number (scene/define_value.h): it is held,
      // keyed and written in the manifest as the number, not as the text ("0x10" and 16 are one point).
      if (const auto n = readDefineNumber(v.text)) {
        if (const std::string problem = sweepNumberProblem(*n); !problem.empty())
          fail(function, what + " = '" + v.text + "'" + problem);
        v.number = n->value;
        v.text.clear();
        return v;
      }
      v.kind = SweepValue::Kind::String;
      return v;
    }
    default:
      fail(function, what + " must be a number, a boolean or a string, got " + typeName(L, index));
  }
}

long long integerArgument(lua_State* L, int index, const std::string& function, const std::string& what) {
  if (!lua_isinteger(L, index)) {
    const double x = lua_type(L, index) == LUA_TNUMBER ? lua_tonumber(L, index) : NAN;
    if (!(std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 9e15))
      fail(function, what + " must be an integer, got " +
                         (lua_type(L, index) == LUA_TNUMBER ? formatNumber(x) : typeName(L, index)));
    return static_cast<long long>(x);
  }
  return static_cast<long long>(lua_tointeger(L, index));
}

// Pairs (string key, value at -1) of the table at `index`, raw; fails on a non-string key.
template <class F>
void forEachNamed(lua_State* L, int index, const std::string& function, F&& f) {
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING)
      fail(function, "keys must be parameter names, got a " + typeName(L, -2) + " key");
    f(std::string(lua_tostring(L, -2)));
    lua_pop(L, 1);
  }
}

int linspace(lua_State* L) {
  if (lua_gettop(L) != 3) fail("linspace", "expected linspace(a, b, n)");
  const SweepValue a = readValue(L, 1, "linspace", "a"), b = readValue(L, 2, "linspace", "b");
  if (a.kind != SweepValue::Kind::Number || b.kind != SweepValue::Kind::Number)
    fail("linspace", "a and b must be numbers");
  const long long n = integerArgument(L, 3, "linspace", "n");
  if (n < 1) fail("linspace", "n = " + std::to_string(n) + " gives an empty range (n must be >= 1)");
  if (n > kMaxSweepPoints) fail("linspace", "n = " + std::to_string(n) + " is more than " + std::to_string(kMaxSweepPoints));
  lua_createtable(L, int(n), 0);
  for (long long i = 0; i < n; ++i) {
    lua_pushnumber(L, linspaceValue(a.number, b.number, n, i));
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

int points(lua_State* L) {
  if (lua_gettop(L) != 1 || !lua_istable(L, 1)) fail("points", "expected points { {name = value, ...}, ... }");
  SweepDeclaration d;
  d.kind = SweepDeclaration::Kind::Points;
  d.origin = LuaSandbox::of(L).here(L).str();
  const lua_Unsigned count = lua_rawlen(L, 1);
  if (count == 0) fail("points", "the list is empty (a sweep needs at least one point)");
  for (lua_Unsigned i = 1; i <= count; ++i) {
    const std::string what = "point [" + std::to_string(i) + "]";
    if (lua_rawgeti(L, 1, lua_Integer(i)) != LUA_TTABLE)
      fail("points", what + " must be a table {name = value, ...}, got " + typeName(L, -1));
    SweepAssignment a;
    forEachNamed(L, lua_gettop(L), "points", [&](const std::string& name) {
      a.emplace_back(name, readValue(L, -1, "points", what + "." + name));
    });
    lua_pop(L, 1);
    std::sort(a.begin(), a.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    if (a.empty()) fail("points", what + " sets no parameter");
    if (!d.points.empty()) {
      auto names = [](const SweepAssignment& s) {
        std::string list;
        for (const auto& [n, v] : s) list += (list.empty() ? "" : ", ") + n;
        return list;
      };
      if (names(a) != names(d.points.front()))
        fail("points", what + " sets {" + names(a) + "} but point [1] sets {" + names(d.points.front()) +
                           "}: every point must set the same parameters");
    }
    d.points.push_back(std::move(a));
  }
  pushUserdata(L, std::move(d));
  return 1;
}

int random(lua_State* L) {
  if (lua_gettop(L) != 1 || !lua_istable(L, 1))
    fail("random", "expected random { n = COUNT, seed = S, name = {lo, hi}, ... }");
  SweepDeclaration d;
  d.kind = SweepDeclaration::Kind::Random;
  d.origin = LuaSandbox::of(L).here(L).str();
  bool haveN = false;
  forEachNamed(L, 1, "random", [&](const std::string& name) {
    if (name == "n") {
      const long long n = integerArgument(L, -1, "random", "'n'");
      if (n < 1) fail("random", "'n' must be >= 1 (a sweep needs at least one point), got " + std::to_string(n));
      if (n > kMaxSweepPoints) fail("random", "'n' = " + std::to_string(n) + " is more than " + std::to_string(kMaxSweepPoints));
      d.count = n;
      haveN = true;
    } else if (name == "seed") {
      const long long s = integerArgument(L, -1, "random", "'seed'");
      if (s < 0 || s > 0xffffffffLL) fail("random", "'seed' must be in 0..4294967295, got " + std::to_string(s));
      d.seed = std::uint32_t(s);
    } else {
      const std::string what = "'" + name + "'";
      if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2)
        fail("random", what + " must be a range {lo, hi}, got " + typeName(L, -1));
      SweepRange r{name};
      for (int k = 0; k < 2; ++k) {
        lua_rawgeti(L, -1, k + 1);
        const SweepValue v = readValue(L, -1, "random", what + (k ? ".hi" : ".lo"));
        if (v.kind != SweepValue::Kind::Number) fail("random", what + ": lo and hi must be numbers");
        (k ? r.hi : r.lo) = v.number;
        lua_pop(L, 1);
      }
      if (!(r.lo < r.hi))
        fail("random", what + " = {" + formatNumber(r.lo) + ", " + formatNumber(r.hi) +
                           "} is an empty range (lo must be < hi)");
      // lo + (hi − lo)·u with hi − lo infinite gives every point the same value (sweep audit).
      if (!std::isfinite(r.hi - r.lo))
        fail("random", what + " = {" + formatNumber(r.lo) + ", " + formatNumber(r.hi) +
                           "}: hi - lo overflows a double, a range this wide cannot be drawn uniformly");
      d.ranges.push_back(r);
    }
  });
  if (!haveN) fail("random", "'n' (the number of points) is required");
  if (d.ranges.empty()) fail("random", "no parameter range given (name = {lo, hi})");
  std::sort(d.ranges.begin(), d.ranges.end(), [](const auto& x, const auto& y) { return x.name < y.name; });
  pushUserdata(L, std::move(d));
  return 1;
}

}  // namespace

void registerSweepFunctions(lua_State* L) {
  registerUserdataType<SweepDeclaration>(L, {});
  lua_register(L, "linspace", &protectedCall<linspace>);
  lua_register(L, "points", &protectedCall<points>);
  lua_register(L, "random", &protectedCall<random>);
}

SweepDeclaration readSweepGlobal(lua_State* L) {
  const std::string path = LuaSandbox::of(L).scenePath();
  lua_pushglobaltable(L);
  lua_pushstring(L, "sweep");
  lua_rawget(L, -2);
  SweepDeclaration d;
  const int top = lua_gettop(L);
  try {
    if (const SweepDeclaration* held = toUserdata<SweepDeclaration>(L, top)) {
      d = *held;
    } else if (lua_istable(L, top)) {
      d.kind = SweepDeclaration::Kind::Grid;
      d.origin = path;
      forEachNamed(L, top, "sweep", [&](const std::string& name) {
        const std::string what = "sweep." + name;
        std::vector<SweepValue> values;
        if (lua_istable(L, -1)) {
          const int list = lua_gettop(L);
          const lua_Unsigned n = lua_rawlen(L, list);
          if (n == 0) fail(what, "empty list (a sweep parameter needs at least one value)");
          for (lua_Unsigned i = 1; i <= n; ++i) {
            lua_rawgeti(L, list, lua_Integer(i));
            values.push_back(readValue(L, -1, what, "value [" + std::to_string(i) + "]"));
            lua_pop(L, 1);
          }
        } else {
          values.push_back(readValue(L, -1, what, "the value"));
        }
        d.grid.push_back({name, std::move(values)});
      });
      if (d.grid.empty()) fail("sweep", "the table is empty (no parameter to sweep)");
      std::sort(d.grid.begin(), d.grid.end(), [](const auto& x, const auto& y) { return x.name < y.name; });
    } else if (!lua_isnil(L, top)) {
      fail("sweep", "must be a table {name = {values}, ...}, points {...} or random {...}, got " + typeName(L, top));
    }
  } catch (const ScriptError& e) {
    lua_settop(L, top - 2);
    lua_getfield(L, LUA_REGISTRYINDEX, kSweepLineKey);
    const lua_Integer line = lua_isinteger(L, -1) ? lua_tointeger(L, -1) : 0;
    lua_pop(L, 1);
    throw InputError(path + (line > 0 ? ":" + std::to_string(line) : "") + ": " + e.what());
  }
  lua_settop(L, top - 2);
  return d;
}

}  // namespace scene

SweepDeclaration loadSweepDeclaration(const std::string& path, const SceneParams& params) {
  SweepDeclaration d;
  scene::loadSceneInspecting(path, params, [&](lua_State* L) { d = scene::readSweepGlobal(L); });
  return d;
}

}  // namespace dicsynth
