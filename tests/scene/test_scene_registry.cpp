// The scene language's registry against its documentation: every constructor and function the
// language adds to Lua appears exactly once in the manual's constructor table
// (docs/scene-language.md), and the table names nothing the language lacks. The registry is read from a Lua state: the
// globals registerSceneLanguage adds to a bare sandbox, and the functions in its constructor tables.
#include <doctest/doctest.h>

#include <lua.hpp>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "scene/constructors.h"
#include "scene/lua_sandbox.h"

using namespace dicsynth::scene;

namespace {

std::set<std::string> globalNames(lua_State* L) {
  std::set<std::string> names;
  lua_pushglobaltable(L);
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    if (lua_type(L, -2) == LUA_TSTRING) names.insert(lua_tostring(L, -2));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return names;
}

// "Camera.Pinhole", "translate", ...: what registerSceneLanguage adds.
std::set<std::string> registry() {
  LuaSandbox bare("<bare>", {0, 0, 0});
  const std::set<std::string> lua = globalNames(bare.state());
  LuaSandbox full("<full>", {0, 0, 0});
  lua_State* L = full.state();
  registerSceneLanguage(L);
  std::set<std::string> out;
  for (const std::string& name : globalNames(L)) {
    if (lua.count(name)) continue;
    lua_getglobal(L, name.c_str());
    if (lua_istable(L, -1)) {
      lua_pushnil(L);
      while (lua_next(L, -2)) {
        if (lua_type(L, -2) == LUA_TSTRING && lua_isfunction(L, -1)) out.insert(name + "." + lua_tostring(L, -2));
        lua_pop(L, 1);
      }
    } else if (lua_isfunction(L, -1)) {
      out.insert(name);
    }
    lua_pop(L, 1);
  }
  return out;
}

}  // namespace

TEST_CASE("scene-registry: the manual's constructor table lists every constructor of the scene language once, and nothing else") {
  std::ifstream in(std::string(DS_SOURCE_DIR) + "/docs/scene-language.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string readme = text.str();
  const std::size_t start = readme.find("| kind | constructors | parameters | see |");
  REQUIRE(start != std::string::npos);
  const std::size_t end = readme.find("\n\n", start);
  const std::string table = readme.substr(start, end - start);
  // Column 2 of each row: the `names` in it.
  std::map<std::string, int> listed;
  std::istringstream rows(table);
  for (std::string row; std::getline(rows, row);) {
    const std::size_t a = row.find('|', 1), b = row.find('|', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string cell = row.substr(a + 1, b - a - 1);
    static const std::regex name("`([A-Za-z_][A-Za-z0-9_.]*)`");
    for (auto it = std::sregex_iterator(cell.begin(), cell.end(), name); it != std::sregex_iterator(); ++it)
      ++listed[(*it)[1].str()];
  }
  const std::set<std::string> actual = registry();
  CHECK(actual.size() > 40);
  for (const std::string& name : actual) {
    INFO(name);
    CHECK(listed.count(name) == 1);
    if (listed.count(name)) CHECK(listed[name] == 1);
  }
  for (const auto& [name, count] : listed) {
    INFO(name);
    CHECK(actual.count(name) == 1);
  }
}
