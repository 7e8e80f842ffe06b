#include "scene/define_value.h"

#include <cmath>

#include <lua.hpp>

#include "core/exact_number.h"

namespace dicsynth {
namespace {

// Lua's own reading of numbers needs a state: one per thread, made on first use and kept (a
// sweep parses millions of values: one state, not one each).
lua_State* parsingState() {
  struct Owner {
    lua_State* L = luaL_newstate();
    ~Owner() { lua_close(L); }
  };
  thread_local Owner owner;
  return owner.L;
}

}  // namespace

std::optional<DefineNumber> readDefineNumber(const std::string& text) {
  lua_State* L = parsingState();
  // lua_stringtonumber stops at a NUL: the whole text must be read (a NUL inside is a string).
  if (text.find('\0') != std::string::npos || lua_stringtonumber(L, text.c_str()) != text.size() + 1) return std::nullopt;
  DefineNumber n;
  n.integerLiteral = lua_isinteger(L, -1);
  if (n.integerLiteral) n.integer = lua_tointeger(L, -1);
  n.value = lua_tonumber(L, -1);
  lua_pop(L, 1);
  return n;
}

std::string sweepNumberProblem(const DefineNumber& n) {
  if (!std::isfinite(n.value)) return " is a number that is not finite";
  if (n.integerLiteral && (n.integer > kExactInteger || n.integer < -kExactInteger))
    return ": a sweep holds its numbers as doubles, exact for integers up to 2^53 (pass a larger integer with -D)";
  return "";
}

bool arrivesAsInteger(double v) {
  return std::isfinite(v) && v == std::floor(v) && std::abs(v) <= kExactIntegerLimit && !(v == 0 && std::signbit(v));
}

std::string defineNumberText(double v) {
  if (arrivesAsInteger(v)) return std::to_string(static_cast<long long>(v));
  // The shortest text that reads back as v ("0.1", not %.17g's "0.10000000000000001"): exact, and
  // the spelling people type, so a -D key of an earlier sweep, which held the text as typed, stays
  // the same for it, and the manifest and --list read as the values were given.
  std::string text = shortestNumber(v);
  // "-0" would read as an integer: a float is written with a point or an exponent.
  if (std::isfinite(v) && text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string canonicalDefineText(const std::string& text) {
  const auto n = readDefineNumber(text);
  if (!n || !std::isfinite(n->value)) return text;
  return n->integerLiteral ? std::to_string(n->integer) : defineNumberText(n->value);
}

bool pushDefineValue(lua_State* L, const std::string& text) {
  if (const auto n = readDefineNumber(text)) {
    if (!std::isfinite(n->value)) return false;
    if (n->integerLiteral)
      lua_pushinteger(L, n->integer);
    else if (arrivesAsInteger(n->value))
      lua_pushinteger(L, static_cast<lua_Integer>(n->value));
    else
      lua_pushnumber(L, n->value);
  } else if (text == "true" || text == "false") {
    lua_pushboolean(L, text == "true");
  } else {
    lua_pushlstring(L, text.data(), text.size());
  }
  return true;
}

}  // namespace dicsynth
