// LuaSandbox: state, allocator with a memory limit, count hook with an instruction limit, the
// restricted library set and the one-line error format. See lua_sandbox.h for the rules.
#include "scene/lua_sandbox.h"

#include "core/exact_number.h"
#include "core/warning.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <lua.hpp>

namespace dicsynth::scene {

namespace {

// True when `message` starts with "<scene>:DIGITS:", the position Lua (or we) put in front.
bool hasPosition(const char* message) {
  const std::size_t n = std::strlen(kChunkToken);
  if (std::strncmp(message, kChunkToken, n) != 0 || message[n] != ':') return false;
  const char* p = message + n + 1;
  if (*p < '0' || *p > '9') return false;
  while (*p >= '0' && *p <= '9') ++p;
  return *p == ':';
}

// Error messages are one line: control line breaks are shown escaped.
std::string oneLine(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else
      out += c;
  }
  return out;
}

#if LUA_VERSION_RELEASE_NUM <= 50404
constexpr bool kCanReadLineWhileAllocating = true;
#else
constexpr bool kCanReadLineWhileAllocating = false;
#endif

}  // namespace

std::string formatNumber(double value) { return shortestNumber(value); }

LuaSandbox::LuaSandbox(std::string scenePath, SandboxLimits limits)
    : scenePath_(std::move(scenePath)),
      sceneDir_(std::filesystem::path(scenePath_).parent_path()),
      limits_(limits) {
  L_ = lua_newstate(&LuaSandbox::allocate, this);
  DS_CHECK(L_ != nullptr, "lua_newstate failed");
  openLibraries();
}

LuaSandbox::~LuaSandbox() {
  enforceMemory_ = false;
  if (L_) lua_close(L_);
}

LuaSandbox& LuaSandbox::of(lua_State* L) {
  void* ud = nullptr;
  lua_getallocf(L, &ud);
  return *static_cast<LuaSandbox*>(ud);
}

int LuaSandbox::currentLine(lua_State* L) {
  // Walk outwards from the running function (level 0) to the first Lua function: C functions
  // (constructors, print, string.rep, the message handler) have no line of their own.
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar); ++level) {
    if (lua_getinfo(L, "l", &ar) && ar.currentline > 0) return ar.currentline;
  }
  return 0;
}

LuaSandbox::UnlimitedScope::UnlimitedScope(lua_State* L)
    : sandbox_(LuaSandbox::of(L)), previous_(sandbox_.unlimited_) {
  sandbox_.unlimited_ = true;
}

LuaSandbox::UnlimitedScope::~UnlimitedScope() { sandbox_.unlimited_ = previous_; }

LuaSandbox::OwnInstructionBudget::OwnInstructionBudget(LuaSandbox& sandbox, const char* what)
    : sandbox_(sandbox), saved_(sandbox.instructions_), savedWhat_(sandbox.budget_) {
  sandbox_.instructions_ = 0;
  sandbox_.budget_ = what;
}

LuaSandbox::OwnInstructionBudget::~OwnInstructionBudget() {
  sandbox_.instructions_ = saved_;
  sandbox_.budget_ = savedWhat_;
}

void LuaSandbox::recordLimit(Limit which, int line) {
  if (exceeded_ != Limit::None) return;  // keep the first: that is where the scene went wrong
  exceeded_ = which;
  exceededLine_ = line;
}

// lua_Alloc. Lua never lets a shrink fail, so only growth is checked. When refusing, record the
// line now: Lua raises LUA_ERRMEM without calling the message handler. L_ is the main thread; in a
// coroutine the line found is that of the coroutine.resume call. Reading the stack from inside
// the allocator is safe up to Lua 5.4.4, which allocates a new stack before touching the old one;
// from 5.4.5 on, stack pointers are offsets while the stack is reallocated, so there the line of
// the last count hook (at most kHookInterval instructions old) is used instead.
void* LuaSandbox::allocate(void* ud, void* ptr, std::size_t oldSize, std::size_t newSize) {
  auto& sandbox = *static_cast<LuaSandbox*>(ud);
  if (ptr == nullptr) oldSize = 0;  // then oldSize tells the kind of object, not a size
  if (newSize == 0) {
    std::free(ptr);
    sandbox.bytesInUse_ -= oldSize;
    return nullptr;
  }
  const std::size_t limit = sandbox.limits_.maxMemoryBytes;
  const std::size_t others = sandbox.bytesInUse_ - oldSize;
  if (newSize > oldSize && sandbox.enforceMemory_ && !sandbox.unlimited_ &&
      (newSize > limit || others > limit - newSize)) {
    sandbox.recordLimit(Limit::Memory, kCanReadLineWhileAllocating && sandbox.L_
                                           ? currentLine(sandbox.L_)
                                           : sandbox.lastHookLine_);
    return nullptr;
  }
  void* grown = std::realloc(ptr, newSize);
  if (grown == nullptr) return nullptr;
  sandbox.bytesInUse_ = others + newSize;
  return grown;
}

// Count hook: adds up instructions; once a limit is exceeded, raises at every instruction.
void LuaSandbox::countHook(lua_State* L, lua_Debug*) {
  LuaSandbox& sandbox = of(L);
  sandbox.instructions_ += kHookInterval;
  if constexpr (!kCanReadLineWhileAllocating) sandbox.lastHookLine_ = currentLine(L);
  if (sandbox.instructions_ > sandbox.limits_.maxInstructions) {
    if (sandbox.exceeded_ == Limit::None) sandbox.exceededBudget_ = sandbox.budget_;
    sandbox.recordLimit(Limit::Instructions, currentLine(L));
  }
  if (sandbox.limits_.maxSeconds > 0 && sandbox.elapsedSeconds() > sandbox.limits_.maxSeconds)
    sandbox.recordLimit(Limit::Time, currentLine(L));
  if (sandbox.exceeded_ == Limit::None) return;
  lua_sethook(L, &LuaSandbox::countHook, LUA_MASKCOUNT, 1);
  // run() replaces this message by the limit's own, with the line recorded first.
  lua_pushfstring(L, "%s:%d: scene exceeded a limit", kChunkToken, currentLine(L));
  lua_error(L);
}

void LuaSandbox::startClock() {
  startNanoseconds_ = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::steady_clock::now().time_since_epoch()).count();
}

double LuaSandbox::elapsedSeconds() const {
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::steady_clock::now().time_since_epoch()).count();
  return 1e-9 * double(now - startNanoseconds_);
}

// string.find / match / gmatch / gsub with the pattern-work bound of the header comment; the
// original function is upvalue 1. Plain Lua values only: a Lua error may longjmp from here.
int LuaSandbox::boundedPattern(lua_State* L) {
  const bool plainFind = lua_toboolean(L, lua_upvalueindex(2)) && lua_toboolean(L, 4);
  if (!plainFind && lua_type(L, 1) == LUA_TSTRING && lua_type(L, 2) == LUA_TSTRING) {
    std::size_t n = 0, m = 0;
    lua_tolstring(L, 1, &n);
    const char* pattern = lua_tolstring(L, 2, &m);
    int quantifiers = 0;
    bool inSet = false;
    for (std::size_t i = 0; i < m; ++i) {
      const char c = pattern[i];
      if (c == '%') {
        ++i;  // an escaped character, or a class (%a, %b xy: its two delimiters are literal)
        if (i < m && pattern[i] == 'b') i += 2;
        continue;
      }
      if (inSet) {
        if (c == ']') inSet = false;
        continue;
      }
      if (c == '[') {
        inSet = true;
        if (i + 1 < m && pattern[i + 1] == '^') ++i;
        if (i + 1 < m && pattern[i + 1] == ']') ++i;  // a leading ] is literal
        continue;
      }
      if (c == '*' || c == '+' || c == '-' || c == '?') ++quantifiers;
    }
    const bool anchored = m > 0 && pattern[0] == '^';
    const double work = std::pow(double(n) + 1, quantifiers + (anchored ? 0 : 1));
    if (work > kMaxPatternWork)
      return luaL_error(L, "%s: a pattern with %d quantifiers on a subject of %d characters may take ~%f steps, over the "
                           "limit of %f (split the subject, anchor the pattern with ^, or use fewer * + - ?)",
                        lua_tostring(L, lua_upvalueindex(3)), quantifiers, int(n), lua_Number(work),
                        lua_Number(kMaxPatternWork));
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// Message handler of the scene's pcall: makes sure the message is a string with a position.
int LuaSandbox::messageHandler(lua_State* L) {
  const char* message = nullptr;
  const int type = lua_type(L, 1);
  if (type == LUA_TSTRING || type == LUA_TNUMBER) {
    message = lua_tostring(L, 1);
  } else if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) {
    message = lua_tostring(L, -1);
  } else {
    message = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  if (hasPosition(message))
    lua_pushstring(L, message);
  else
    lua_pushfstring(L, "%s:%d: %s", kChunkToken, currentLine(L), message);
  return 1;
}

// print(...): one line "PATH:LINE: v1<TAB>v2..." on stderr, written at once.
int LuaSandbox::print(lua_State* L) {
  LuaSandbox& sandbox = of(L);
  if (sandbox.quiet()) return 0;
  const int n = lua_gettop(L);
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  luaL_addstring(&b, sandbox.scenePath_.c_str());
  lua_pushfstring(L, ":%d: ", currentLine(L));
  luaL_addvalue(&b);
  for (int i = 1; i <= n; ++i) {
    if (i > 1) luaL_addchar(&b, '\t');
    // One line per print: a newline or carriage return inside a value is written as \n or \r, so
    // that scene output can never look like a line of its own (an error line, say).
    std::size_t length = 0;
    const char* value = luaL_tolstring(L, i, &length);
    for (std::size_t k = 0; k < length; ++k) {
      if (value[k] == '\n') luaL_addstring(&b, "\\n");
      else if (value[k] == '\r') luaL_addstring(&b, "\\r");
      else luaL_addchar(&b, value[k]);
    }
    lua_pop(L, 1);
  }
  luaL_pushresult(&b);
  std::size_t length = 0;
  const char* text = lua_tolstring(L, -1, &length);
  note(std::string(text, length));  // stderr's line; sys.stderr in Python (core/warning.h)
  return 0;
}

// setmetatable(t, mt) that refuses a metatable with __gc (upvalue 1: the original setmetatable).
int LuaSandbox::setmetatableNoGc(lua_State* L) {
  if (lua_type(L, 2) == LUA_TTABLE) {
    lua_pushliteral(L, "__gc");
    if (lua_rawget(L, 2) != LUA_TNIL)
      return luaL_error(L,
                        "setmetatable: __gc metamethods are not allowed in scenes (finalizers "
                        "run outside the instruction limit)");
    lua_pop(L, 1);
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

void LuaSandbox::openLibraries() {
  lua_State* L = L_;
  // Only these; io, os, package and debug are never opened.
  static const luaL_Reg kLibraries[] = {
      {LUA_GNAME, luaopen_base},        {LUA_TABLIBNAME, luaopen_table},
      {LUA_STRLIBNAME, luaopen_string}, {LUA_MATHLIBNAME, luaopen_math},
      {LUA_UTF8LIBNAME, luaopen_utf8},  {LUA_COLIBNAME, luaopen_coroutine},
  };
  for (const luaL_Reg& library : kLibraries) {
    luaL_requiref(L, library.name, library.func, 1);
    lua_pop(L, 1);
  }
  // Remove what reads files, loads code or drives the collector.
  for (const char* name : {"dofile", "loadfile", "load", "require", "collectgarbage"}) {
    lua_pushnil(L);
    lua_setglobal(L, name);
  }
  lua_getglobal(L, LUA_STRLIBNAME);
  lua_pushnil(L);
  lua_setfield(L, -2, "dump");
  // Pattern functions with a work bound (header comment). Strings' methods (s:find) use this same
  // table through the string metatable's __index.
  for (const char* name : {"find", "match", "gmatch", "gsub"}) {
    lua_getfield(L, -1, name);
    lua_pushboolean(L, std::strcmp(name, "find") == 0);  // find's 4th argument: plain
    lua_pushfstring(L, "string.%s", name);
    lua_pushcclosure(L, &LuaSandbox::boundedPattern, 3);
    lua_setfield(L, -2, name);
  }
  lua_pop(L, 1);

  lua_pushcfunction(L, &LuaSandbox::print);
  lua_setglobal(L, "print");
  lua_getglobal(L, "setmetatable");
  lua_pushcclosure(L, &LuaSandbox::setmetatableNoGc, 1);
  lua_setglobal(L, "setmetatable");

  // Deterministic random numbers: same scene, same numbers.
  lua_getglobal(L, LUA_MATHLIBNAME);
  lua_getfield(L, -1, "randomseed");
  lua_pushinteger(L, static_cast<lua_Integer>(kRandomSeed));
  lua_call(L, 1, 0);
  lua_pop(L, 1);
}

std::string LuaSandbox::formatMessage(const std::string& luaMessage, int fallbackLine) const {
  // Every "<scene>:N:" names the scene (a message re-raised with error(msg) holds two).
  std::string message;
  const std::size_t tokenLength = std::strlen(kChunkToken);
  for (std::size_t i = 0; i < luaMessage.size();) {
    if (hasPosition(luaMessage.c_str() + i)) {
      message += scenePath_;
      i += tokenLength;
    } else {
      message += luaMessage[i++];
    }
  }
  if (!hasPosition(luaMessage.c_str()))
    message = scenePath_ + ":" + std::to_string(fallbackLine) + ": " + message;
  return oneLine(message);
}

void LuaSandbox::run(const std::string& sourceText) {
  lua_State* L = L_;
  // Like luaL_loadfile: skip a UTF-8 byte-order mark and a first line starting with '#'
  // (keeping its newline so that line numbers stay right).
  std::string source = sourceText;
  if (source.rfind("\xEF\xBB\xBF", 0) == 0) source.erase(0, 3);
  if (!source.empty() && source[0] == '#') source.erase(0, source.find('\n'));

  lua_settop(L, 0);
  lua_pushcfunction(L, &LuaSandbox::messageHandler);
  const std::string chunkName = std::string("=") + kChunkToken;
  int status = luaL_loadbufferx(L, source.data(), source.size(), chunkName.c_str(), "t");
  if (status != LUA_OK) {
    std::string message = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "cannot load";
    lua_settop(L, 0);
    throw InputError(formatMessage(message, 1));
  }

  instructions_ = 0;
  exceeded_ = Limit::None;
  exceededBudget_ = nullptr;
  startClock();
  lua_sethook(L, &LuaSandbox::countHook, LUA_MASKCOUNT, kHookInterval);
  enforceMemory_ = true;
  status = lua_pcall(L, 0, 0, 1);
  enforceMemory_ = false;
  lua_sethook(L, nullptr, 0, 0);
  std::string message;
  if (status != LUA_OK && lua_type(L, -1) == LUA_TSTRING) message = lua_tostring(L, -1);
  lua_settop(L, 0);

  const std::string at = scenePath_ + ":" + std::to_string(exceededLine_) + ": ";
  if (exceeded_ == Limit::Instructions)
    throw InputError(at + "scene exceeded the instruction limit (" + std::to_string(limits_.maxInstructions) +
                     " instructions" + (exceededBudget_ ? std::string(" in ") + exceededBudget_ : std::string()) + ")");
  if (exceeded_ == Limit::Time)
    throw InputError(at + "scene exceeded the time limit (" + formatNumber(limits_.maxSeconds) +
                     " s of evaluation; DICSYNTH_SCENE_SECONDS sets another)");
  if (exceeded_ == Limit::Memory)
    throw InputError(at + "scene exceeded the memory limit (" +
                     formatNumber(static_cast<double>(limits_.maxMemoryBytes) / (1 << 20)) +
                     " MiB)");
  if (status == LUA_ERRMEM)
    throw InputError(scenePath_ + ": out of memory while running the scene");
  if (status != LUA_OK) throw InputError(formatMessage(message, currentLine(L)));
}

void LuaSandbox::callAfterRun(const std::function<void()>& body) {
  std::lock_guard<std::mutex> lock(afterRun_);
  lua_State* L = L_;
  struct Limits {
    LuaSandbox& s;
    explicit Limits(LuaSandbox& sandbox) : s(sandbox) {
      s.instructions_ = 0;
      s.exceeded_ = Limit::None;
      s.exceededBudget_ = nullptr;
      s.startClock();
      lua_sethook(s.L_, &LuaSandbox::countHook, LUA_MASKCOUNT, kHookInterval);
      s.enforceMemory_ = true;
    }
    ~Limits() {
      s.enforceMemory_ = false;
      lua_sethook(s.L_, nullptr, 0, 0);
      lua_settop(s.L_, 0);
    }
  } limits(*this);
  lua_settop(L, 0);
  body();
}

void LuaSandbox::call(int nargs, int nresults) {
  lua_State* L = L_;
  const int base = lua_gettop(L) - nargs;  // the function's index
  lua_pushcfunction(L, &LuaSandbox::messageHandler);
  lua_insert(L, base);
  const int status = lua_pcall(L, nargs, nresults, base);
  lua_remove(L, base);
  if (status == LUA_OK) return;
  std::string message;
  if (lua_type(L, -1) == LUA_TSTRING) message = lua_tostring(L, -1);
  lua_settop(L, base - 1);
  const std::string at = scenePath_ + ":" + std::to_string(exceededLine_) + ": ";
  if (exceeded_ == Limit::Instructions)
    throw InputError(at + "exceeded the instruction limit (" + std::to_string(limits_.maxInstructions) +
                     " instructions) in " + (exceededBudget_ ? exceededBudget_ : "one batch of calls after the scene ran"));
  if (exceeded_ == Limit::Time)
    throw InputError(at + "exceeded the time limit (" + formatNumber(limits_.maxSeconds) +
                     " s) in one batch of calls after the scene ran");
  if (exceeded_ == Limit::Memory)
    throw InputError(at + "exceeded the memory limit (" +
                     formatNumber(static_cast<double>(limits_.maxMemoryBytes) / (1 << 20)) + " MiB)");
  if (status == LUA_ERRMEM) throw InputError(scenePath_ + ": out of memory in a call after the scene ran");
  throw InputError(formatMessage(message, currentLine(L)));
}

}  // namespace dicsynth::scene
