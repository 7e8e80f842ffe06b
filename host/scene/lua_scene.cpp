// loadScene: runs a scene file in a LuaSandbox with the scene language, the global `frame` and the
// -D defines, then collects the cameras, objects, lights and rigs the scene assigned to globals.
//
// Collection rule: after the chunk has run, every global variable whose value is a Camera, an
// Object or a Light is part of the scene, named by the variable; a global Rig `rig` adds its two
// posed cameras as "rig.left" and "rig.right" and the rig itself to Scene::rigs. Values reachable
// only through tables or locals (lights = { Light.Point{...} }) are NOT collected: assign them to
// globals, e.g. _G["light" .. i] = Light.Point { ... }. Each list is sorted by name (Lua's table
// order is not deterministic); objectId = index + 1 follows that order.
//
// Defines (-D name=value) are not globals: _G's metatable serves them through __index and records
// each read, so that a define the scene never reads (a typo) is an error. A value is a number when
// Lua reads the whole text as one, true/false as booleans, otherwise a string.
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "core/c_locale.h"
#include "core/closest_name.h"
#include "core/crc32.h"
#include "core/option_names.h"
#include "core/warning.h"
#include "scene/constructors.h"
#include "scene/define_value.h"
#include "scene/lua_sandbox.h"
#include "scene/lua_values.h"
#include "scene/scene.h"
#include "scene/sweep_declaration.h"

namespace dicsynth {

namespace scene {

void registerSceneLanguage(lua_State* L) {
  registerCameraConstructors(L);
  registerShapeConstructors(L);
  registerNurbsConstructors(L);
  registerDeformConstructors(L);
  registerObjectConstructors(L);
  registerShadingConstructors(L);
  registerTransformFunctions(L);
  registerTargetConstructors(L);
  registerRigConstructors(L);
  registerSensorConstructors(L);
  registerSweepFunctions(L);
}

namespace {

constexpr const char* kDefinesReadKey = "dicsynth.definesRead";  // registry: set of names read
constexpr const char* kUnsetReadKey = "dicsynth.unsetRead";      // registry: globals read unset

std::string readSceneFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": cannot read the scene file: it is a folder");
  // Devices and pipes are refused (reading /dev/zero never ends), and so are files beyond
  // kMaxSceneFileBytes: a scene is a program; data belongs in the files it names.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(path + ": cannot read the scene file: not a regular file");
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxSceneFileBytes)
    throw InputError(path + ": cannot read the scene file: " + std::to_string(size) + " bytes, over the limit of " +
                     std::to_string(kMaxSceneFileBytes) + " (16 MiB)");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr)
    throw InputError(path + ": cannot read the scene file: " + std::strerror(errno));
  // The file opened is checked again, and read to the limit at most: the path checked above may
  // name another file by now (a link swapped to /dev/zero, a file still growing), which was read
  // without end (the sandbox audit of 2026-11-28).
  struct stat opened {};
  if (::fstat(::fileno(file), &opened) != 0 || !S_ISREG(opened.st_mode)) {
    std::fclose(file);
    throw InputError(path + ": cannot read the scene file: not a regular file");
  }
  std::string text;
  char buffer[1 << 16];
  std::size_t n = 0;
  while (text.size() <= kMaxSceneFileBytes && (n = std::fread(buffer, 1, sizeof buffer, file)) > 0) text.append(buffer, n);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw InputError(path + ": cannot read the scene file: read error");
  if (text.size() > kMaxSceneFileBytes)
    throw InputError(path + ": cannot read the scene file: more than " + std::to_string(kMaxSceneFileBytes) +
                     " bytes, over the limit (16 MiB)");
  return text;
}

bool isLuaIdentifier(const std::string& name) {
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (name.empty() || !letter(name[0])) return false;
  return std::all_of(name.begin(), name.end(), [&](char c) { return letter(c) || digit(c); });
}

bool isLuaKeyword(const std::string& name) {
  static const std::set<std::string> kKeywords = {
      "and",      "break",  "do",   "else", "elseif", "end",  "false", "for",
      "function", "goto",   "if",   "in",   "local",  "nil",  "not",   "or",
      "repeat",   "return", "then", "true", "until",  "while"};
  return kKeywords.count(name) > 0;
}

// _G.__newindex (a global assigned for the first time): for `sweep`, keeps the line in the registry
// (kSweepLineKey: a grid table is read after the run, and its errors name this line); then assigns.
int assignGlobal(lua_State* L) {
  if (lua_type(L, 2) == LUA_TSTRING && std::strcmp(lua_tostring(L, 2), "sweep") == 0) {
    lua_pushinteger(L, LuaSandbox::currentLine(L));
    lua_setfield(L, LUA_REGISTRYINDEX, kSweepLineKey);
  }
  lua_settop(L, 3);
  lua_rawset(L, 1);
  return 0;
}

constexpr int kMaxUnsetRecorded = 256;

// _G.__index: serves a define (upvalue 1: name → value) and records the read (upvalue 2); a name
// that is no define is recorded in upvalue 3 (at most kMaxUnsetRecorded, counted in upvalue 4), the
// globals read unset that an unread define may be a typo of.
int readDefine(lua_State* L) {
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) == LUA_TNIL) {
    const lua_Integer recorded = lua_tointeger(L, lua_upvalueindex(4));
    // Names of identifiers' length only: a scene reading _G[two megabytes .. i] kept those strings
    // alive and passed the memory limit (the review of 2026-11-29).
    if (lua_type(L, 2) == LUA_TSTRING && lua_rawlen(L, 2) <= 64 && recorded < kMaxUnsetRecorded) {
      lua_pushvalue(L, 2);
      if (lua_rawget(L, lua_upvalueindex(3)) == LUA_TNIL) {
        lua_pushvalue(L, 2);
        lua_pushboolean(L, 1);
        lua_rawset(L, lua_upvalueindex(3));
        lua_pushinteger(L, recorded + 1);
        lua_replace(L, lua_upvalueindex(4));
      }
      lua_pop(L, 1);
    }
    return 1;  // the nil
  }
  lua_pushvalue(L, 2);
  lua_pushboolean(L, 1);
  lua_rawset(L, lua_upvalueindex(2));
  return 1;
}

// Checks the defines and installs _G's metatable. Runs before the scene (limits not enforced).
void installDefines(lua_State* L, const std::vector<std::pair<std::string, std::string>>& defines) {
  lua_newtable(L);  // name → value
  const int values = lua_gettop(L);
  for (const auto& [name, value] : defines) {
    const std::string option = defineName(name) + ": ";
    if (!isLuaIdentifier(name))
      throw InputError(
          option + "'" + name +
          "' is not a Lua identifier (letters, digits and _, not starting with a digit)");
    if (isLuaKeyword(name)) throw InputError(option + "'" + name + "' is a Lua keyword");
    if (name == "frame")
      throw InputError(option + (optionSpelling() == OptionSpelling::Cli
                                   ? "'frame' is reserved: the frame number is set by --frames "
                                     "(render) or --frame (compare), not by -D"
                                   : "'frame' is reserved: the frame number is set by render's frames"));
    lua_pushglobaltable(L);
    const bool builtIn = lua_getfield(L, -1, name.c_str()) != LUA_TNIL;
    lua_pop(L, 2);
    if (builtIn)
      throw InputError(option + "'" + name + "' is a built-in name of the scene language");
    lua_getfield(L, values, name.c_str());
    const bool twice = !lua_isnil(L, -1);
    lua_pop(L, 1);
    if (twice) throw InputError(option + "defined twice");
    if (!pushDefineValue(L, value)) throw InputError(option + "'" + value + "' is a number that is not finite");
    lua_setfield(L, values, name.c_str());
  }
  lua_newtable(L);  // names read
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, kDefinesReadKey);
  lua_newtable(L);  // globals read unset
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, kUnsetReadKey);

  lua_pushglobaltable(L);
  lua_createtable(L, 0, 3);  // _G's metatable
  lua_pushvalue(L, values);
  lua_pushvalue(L, values + 1);
  lua_pushvalue(L, values + 2);
  lua_pushinteger(L, 0);
  lua_pushcclosure(L, &readDefine, 4);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, &assignGlobal);
  lua_setfield(L, -2, "__newindex");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");  // the scene cannot replace or inspect it
  lua_setmetatable(L, -2);
  lua_settop(L, values - 1);
}

// `unsetRead`: the globals the scene read unset (Scene::unsetGlobalsRead), the names a define may
// have been meant as: `-D strian=0.003` said only that the scene never reads 'strian' (the docs walk
// of 2026-11-29).
[[noreturn]] void refuseUnreadDefine(const std::string& scenePath, const std::string& name,
                                     const std::vector<std::string>& sweepParameters,
                                     const std::vector<std::string>& unsetRead) {
  const std::optional<std::string> near = closestName(name, unsetRead);
  const std::string hint = near ? " (did you mean '" + *near + "'?)" : "";
  if (std::find(sweepParameters.begin(), sweepParameters.end(), name) != sweepParameters.end())
    throw InputError(scenePath + ": sweep parameter '" + name + "': the scene never reads '" + name + "'" + hint +
                     " (a typo in the sweep, or a scene that ignores it)");
  throw InputError(defineName(name) + ": the scene never reads '" + name + "'" + hint);
}

// The globals the evaluation read unset, sorted.
std::vector<std::string> unsetGlobalsRead(lua_State* L) {
  std::vector<std::string> names;
  lua_getfield(L, LUA_REGISTRYINDEX, kUnsetReadKey);
  if (lua_istable(L, -1)) {
    lua_pushnil(L);
    while (lua_next(L, -2) != 0) {
      if (lua_type(L, -2) == LUA_TSTRING) names.emplace_back(lua_tostring(L, -2));
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  std::sort(names.begin(), names.end());
  return names;
}

// The defines the evaluation did not read, in the order given.
std::vector<std::string> unreadDefines(lua_State* L, const std::vector<std::pair<std::string, std::string>>& defines) {
  std::vector<std::string> unread;
  lua_getfield(L, LUA_REGISTRYINDEX, kDefinesReadKey);
  for (const auto& define : defines) {
    const bool read = lua_getfield(L, -1, define.first.c_str()) != LUA_TNIL;
    lua_pop(L, 1);
    if (!read) unread.push_back(define.first);
  }
  lua_pop(L, 1);
  return unread;
}

template <class T>
void sortByName(std::vector<T>& items) {
  std::sort(items.begin(), items.end(), [](const T& a, const T& b) { return a.name < b.name; });
}

// A Rig global as collectGlobals finds it: the identities (userdata addresses) of its Lua values.
// They stay valid while collectGlobals runs: the globals keep the rigs, the rigs their user values.
struct RigGlobal {
  std::string name;
  const StereoRigValue* rig = nullptr;
  const void* posed[2] = {nullptr, nullptr};  // rig.left, rig.right
  const void* given[2] = {nullptr, nullptr};  // the cameras passed as left and right
};

RigGlobal rigGlobal(lua_State* L, std::string name, const StereoRigValue* rig) {
  RigGlobal g{std::move(name), rig};
  const int index = lua_gettop(L);
  for (int side = 0; side < 2; ++side) {
    lua_getiuservalue(L, index, kRigPosedLeft + side);
    g.posed[side] = lua_touserdata(L, -1);
    lua_getiuservalue(L, index, kRigGivenLeft + side);
    g.given[side] = lua_touserdata(L, -1);
    lua_pop(L, 2);
  }
  return g;
}

// Every global Camera is rendered, so a rig's camera that is also a global would be rendered twice
// (once without the rig's pose): refused, at the rig's line.
void checkRigCamerasNotGlobals(const RigGlobal& rig,
                               const std::vector<std::pair<const void*, std::string>>& cameraGlobals) {
  const char* sides[2] = {"left", "right"};
  for (const auto& [identity, global] : cameraGlobals) {
    for (int side = 0; side < 2; ++side) {
      const std::string prefix = "Rig.Stereo '" + rig.name + "': ";
      if (identity == rig.given[side])
        throw InputError(rig.rig->where,
                         prefix + "its " + sides[side] + " camera is also the global '" + global +
                             "', which would be rendered as an extra camera without the rig's pose; "
                             "make it local (local " + global + " = Camera.Pinhole { ... }) or write "
                             "it inside the rig");
      if (identity == rig.posed[side])
        throw InputError(rig.rig->where,
                         prefix + "the global '" + global + "' holds " + rig.name + "." +
                             sides[side] + ", which is already rendered as '" + rig.name + "." +
                             sides[side] + "'; make '" + global + "' local");
    }
  }
}

// A scene can make any string a global's name (_G["..."] = ...), and the names of cameras, rigs,
// objects and lights leave the scene: as file names (<camera>_<frame>.exr, <rig>.yml, written in
// the output folder: a '/' or a leading '.' would write beside it, over "." or "..", or as one of
// the run's hidden temporary files), as entries of comma-separated lists (the EXR header's
// dicsynth:objects), as CSV fields (a target's features) and in the sweep manifest's
// space-separated file list (a camera "left cam" split into two paths that do not exist: sweep
// audit of 2026-11-28). So a name is refused, before any work, when it is empty, begins with '.',
// or holds '/', ',', '"', a space or a control character. Returns what is wrong, or "" for a
// good name.
std::string nameProblem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name[0] == '.') return "begins with '.'";
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) return "holds a control character";
    if (c == '/' || c == ',' || c == '"') return std::string("holds '") + c + "'";
    if (c == ' ') return "holds a space";
  }
  return "";
}

// The name as an error line can show it: control characters as \xNN, at most 40 bytes.
std::string printableName(const std::string& name) {
  std::string out;
  for (const char c : name.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return name.size() > 40 ? out + "..." : out;
}

void checkName(const char* kind, const std::string& name, const SourceLoc& where) {
  const std::string problem = nameProblem(name);
  if (!problem.empty())
    throw InputError(where, std::string("the ") + kind + " name '" + printableName(name) + "' " + problem +
                                "; names of cameras, rigs, objects and lights become file names and list "
                                "entries: use letters, digits, '_', '-' and '.' (not first)");
}

// Copies every Camera, Object, Light and Rig held by a global (string key) into the scene.
Scene collectGlobals(lua_State* L, const std::string& path) {
  Scene scene;
  scene.file = path;
  std::vector<std::pair<const void*, std::string>> cameraGlobals;
  std::vector<RigGlobal> rigs;
  // Every global is collected, so `plate2 = plate` renders the object twice (two coincident
  // surfaces), a camera alias renders its images twice and a light alias doubles the light, all
  // without a word (the new-user trial of 2026-11-28). Said once per pair: a warning, not an error
  // (the scene renders as documented). By the value's identity: names in the order met, sorted below.
  std::map<const void*, std::vector<std::string>> holders;
  std::map<const void*, std::pair<const char*, SourceLoc>> kinds;
  const auto noteHolder = [&](const char* kind, const SourceLoc& where, const std::string& name) {
    const void* id = lua_touserdata(L, -1);
    holders[id].push_back(name);
    kinds.emplace(id, std::make_pair(kind, where));
  };
  lua_pushglobaltable(L);
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_type(L, -1) == LUA_TUSERDATA) {
      const std::string name = lua_tostring(L, -2);
      if (const Camera* camera = toUserdata<Camera>(L, -1)) {
        checkName("camera", name, camera->where);
        noteHolder("camera", camera->where, name);
        scene.cameras.push_back(*camera);
        scene.cameras.back().name = name;
        cameraGlobals.emplace_back(lua_touserdata(L, -1), name);
      } else if (const Object* object = toUserdata<Object>(L, -1)) {
        checkName("object", name, object->where);
        noteHolder("object", object->where, name);
        scene.objects.push_back(*object);
        scene.objects.back().name = name;
      } else if (const Light* light = toUserdata<Light>(L, -1)) {
        checkName("light", name, light->where);
        noteHolder("light", light->where, name);
        scene.lights.push_back(*light);
        scene.lights.back().name = name;
      } else if (const StereoRigValue* rig = toUserdata<StereoRigValue>(L, -1)) {
        checkName("rig", name, rig->where);
        noteHolder("rig", rig->where, name);
        rigs.push_back(rigGlobal(L, name, rig));
      }
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::vector<std::pair<std::string, std::string>> aliases;  // (first name, warning), said in name order
  for (auto& [id, names] : holders) {
    if (names.size() < 2) continue;
    std::sort(names.begin(), names.end());
    const auto& [kind, where] = kinds.at(id);
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
      list += (i == 0 ? "'" : i + 1 == names.size() ? "' and '" : "', '") + names[i];
    const std::string effect = std::string(kind) == "light"    ? "shines " + std::to_string(names.size()) + " times as bright"
                               : std::string(kind) == "object" ? "is rendered " + std::to_string(names.size()) + " times, its surfaces coincident"
                                                               : "is rendered " + std::to_string(names.size()) + " times";
    aliases.emplace_back(names.front(), where.str() + ": the globals " + list + "' hold the same " + kind + ", which " +
                                            effect + " (every global is collected: keep one name, or make the others `local`)");
  }
  std::sort(aliases.begin(), aliases.end());
  for (const auto& [first, text] : aliases) warnAtMost("scene alias: " + text, 1, text);

  // A rig `rig` contributes the cameras "rig.left" and "rig.right".
  for (const RigGlobal& rig : rigs) {
    checkRigCamerasNotGlobals(rig, cameraGlobals);
    StereoRig stereo{rig.name, rig.rig->where, rig.name + ".left", rig.name + ".right"};
    // Only _G["rig.left"] = Camera.Pinhole { ... } can take a rig camera's name; outputs are named
    // after cameras, so two cameras of one name would overwrite each other's files. Named at the
    // rig's line and the global camera's (a camera's own line may be inside a helper function that
    // made both: the 360° trial of 2026-11-29 was pointed at its `lens()` helper).
    for (const std::string* side : {&stereo.left, &stereo.right})
      for (const Camera& global : scene.cameras)
        if (global.name == *side)
          throw InputError(rig.rig->where, "Rig.Stereo '" + rig.name + "': its " + (side == &stereo.left ? "left" : "right") +
                                               " camera is named '" + *side + "', and so is a global camera (made at line " +
                                               std::to_string(global.where.line) + "): rename the global");
    scene.cameras.push_back(rig.rig->left);
    scene.cameras.back().name = stereo.left;
    scene.cameras.push_back(rig.rig->right);
    scene.cameras.back().name = stereo.right;
    scene.rigs.push_back(std::move(stereo));
  }
  sortByName(scene.cameras);
  sortByName(scene.rigs);
  sortByName(scene.objects);
  sortByName(scene.lights);
  // A rig camera in the pose and resolution of another camera is most likely one camera made twice
  // (a ring of Rig.Stereo whose right camera is the next one's left: the 360° trial of 2026-11-29):
  // rendered twice, with other samples and noise (the camera index differs), so not even the same
  // image. (Two global cameras in one pose: an alias is warned above, a deliberate pair is allowed.)
  const auto inRig = [&](const Camera& camera) {
    return std::any_of(scene.rigs.begin(), scene.rigs.end(),
                       [&](const StereoRig& r) { return r.left == camera.name || r.right == camera.name; });
  };
  for (std::size_t a = 0; a < scene.cameras.size(); ++a)
    for (std::size_t b = a + 1; b < scene.cameras.size(); ++b) {
      const Camera &first = scene.cameras[a], &second = scene.cameras[b];
      if (!inRig(first) && !inRig(second)) continue;
      double difference = 0;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          difference = std::max(difference, std::abs(first.worldFromCamera[c][r] - second.worldFromCamera[c][r]));
      if (difference <= 1e-12 && first.width_px == second.width_px && first.height_px == second.height_px)
        warnAtMost("scene cameras in one pose", 10,
                   first.where.str() + ": the cameras '" + first.name + "' and '" + second.name +
                       "' have the same pose and resolution: one camera rendered twice, each with its own samples and "
                       "noise? (a ring of rigs sharing cameras: docs/scene-language.md, \"More than two cameras\")",
                   " (further cameras in one pose not reported)");
    }
  // (Refused above, at the rig.)
  for (std::size_t i = 1; i < scene.cameras.size(); ++i)
    DS_CHECK(scene.cameras[i].name != scene.cameras[i - 1].name, "two cameras named '" + scene.cameras[i].name + "'");
  // Camera names become file names (<camera>_<frame>.exr plus a temporary suffix while written):
  // kMaxCameraNameBytes leaves room under the file systems' 255 bytes.
  for (const Camera& camera : scene.cameras)
    if (camera.name.size() > kMaxCameraNameBytes)
      throw InputError(camera.where, "the camera name '" + camera.name.substr(0, 40) + "...' is " +
                                         std::to_string(camera.name.size()) + " bytes long; names become file names: at most " +
                                         std::to_string(kMaxCameraNameBytes));
  return scene;
}

}  // namespace
}  // namespace scene

// The time limit of an evaluation: SceneParams::maxSeconds, else $DICSYNTH_SCENE_SECONDS, else 60 s.
static double sceneSeconds(const SceneParams& params) {
  if (params.maxSeconds > 0) return params.maxSeconds;
  if (const char* text = std::getenv("DICSYNTH_SCENE_SECONDS")) {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(seconds > 0) || !std::isfinite(seconds))
      throw InputError(std::string("DICSYNTH_SCENE_SECONDS=") + text + ": expected a number of seconds > 0");
    return seconds;
  }
  return 60;
}

bool isSceneLanguageName(const std::string& name) {
  if (scene::isLuaKeyword(name)) return true;
  scene::LuaSandbox sandbox("<names>", {0, 0, 0});
  lua_State* L = sandbox.state();
  scene::registerSceneLanguage(L);
  lua_pushglobaltable(L);
  const bool builtIn = lua_getfield(L, -1, name.c_str()) != LUA_TNIL || name == "frame";
  lua_pop(L, 2);
  return builtIn;
}

Scene loadScene(const std::string& path, const SceneParams& params) {
  return scene::loadSceneInspecting(path, params, nullptr);
}

Scene scene::loadSceneInspecting(const std::string& path, const SceneParams& params,
                                 const std::function<void(lua_State*)>& inspect) {
  const CLocaleScope cLocale;  // the -D values converted, the scene run, in the "C" locale (core/c_locale.h)
  const std::string source = scene::readSceneFile(path);
  // Shared: a Nurbs.deform field keeps a weak_ptr to call it again, the Scene the owning pointer.
  const auto sandbox = std::make_shared<scene::LuaSandbox>(
      path, scene::SandboxLimits{params.maxInstructions, params.maxMemoryBytes, sceneSeconds(params), params.quiet});
  lua_State* L = sandbox->state();
  {
    std::string evaluation = path + '\n' + std::to_string(std::hash<std::string>{}(source)) + '\n' +
                             std::to_string(params.frame);
    for (const auto& [name, value] : params.defines) evaluation += '\n' + name + '=' + value;
    sandbox->setEvaluation(std::move(evaluation));
  }
  scene::registerSceneLanguage(L);
  lua_pushinteger(L, params.frame);
  lua_setglobal(L, "frame");
  scene::installDefines(L, params.defines);

  sandbox->run(source);

  std::vector<std::string> unread = scene::unreadDefines(L, params.defines);
  std::vector<std::string> unsetRead = scene::unsetGlobalsRead(L);
  if (params.requireDefinesRead && !unread.empty())
    scene::refuseUnreadDefine(path, unread.front(), params.sweepParameters, unsetRead);
  if (inspect) inspect(L);
  Scene scene = scene::collectGlobals(L, path);
  scene.unreadDefines = std::move(unread);
  scene.unsetGlobalsRead = std::move(unsetRead);
  scene.sourceCrc32 = crc32Of(source);
  for (const Object& object : scene.objects)
    if (object.shape.deformation && !scene.keepAlive) scene.keepAlive = sandbox;
  if (scene.cameras.empty())
    throw InputError(path + ": the scene defines no camera (assign Camera.Pinhole{…} to a global)");
  return scene;
}

void UnreadDefines::add(const Scene& scene) {
  for (const std::string& name : scene.unsetGlobalsRead)
    if (unsetRead_.size() < std::size_t(scene::kMaxUnsetRecorded) &&
        std::find(unsetRead_.begin(), unsetRead_.end(), name) == unsetRead_.end())
      unsetRead_.push_back(name);
  if (!std::exchange(any_, true)) {
    unread_ = scene.unreadDefines;
    return;
  }
  std::erase_if(unread_, [&](const std::string& name) {
    return std::find(scene.unreadDefines.begin(), scene.unreadDefines.end(), name) == scene.unreadDefines.end();
  });
}

void UnreadDefines::check(const std::string& scenePath, const std::vector<std::string>& sweepParameters) const {
  if (!unread_.empty()) scene::refuseUnreadDefine(scenePath, unread_.front(), sweepParameters, unsetRead_);
}

}  // namespace dicsynth
