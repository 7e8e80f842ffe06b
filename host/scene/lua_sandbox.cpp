// LuaSandbox: state, allocator with a memory limit, count hook with an instruction limit, the
// restricted library set and the one-line error format. See lua_sandbox.h for the rules.
#include "scene/lua_sandbox.h"

#include "core/c_locale.h"
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

}  // namespace

std::string escapeControls(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  escapeControlsTo(text, [&out](const char* piece, std::size_t length) { out.append(piece, length); });
  return out;
}

namespace {

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
  sandbox.lastHookLine_ = currentLine(L);  // the allocator's line on newer Lua, and the clock's at the end
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
        // %bxy scans up to the rest of the subject for its closing y, and a back-reference %1..%9
        // compares up to a capture's length: each is a factor n as a quantifier is (the sandbox
        // audit of 2026-11-28: "%b()" on a million "(" was allowed and took minutes).
        if (i < m && pattern[i] == 'b') {
          ++quantifiers;
          i += 2;
        } else if (i < m && pattern[i] >= '1' && pattern[i] <= '9') {
          ++quantifiers;
        }
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
    // gmatch has no anchor: a leading ^ is matched at every start (Lua 5.4).
    const bool anchored = m > 0 && pattern[0] == '^' && lua_toboolean(L, lua_upvalueindex(4));
    const double work = std::pow(double(n) + 1, quantifiers + (anchored ? 0 : 1));
    if (work > kMaxPatternWork)
      return luaL_error(L, "%s: a pattern with %d quantifiers (* + - ?, %%b, %%1..%%9) on a subject of %d characters may "
                           "take ~%f steps, over the limit of %f (split the subject, anchor the pattern with ^, or "
                           "use fewer quantifiers)",
                        lua_tostring(L, lua_upvalueindex(3)), quantifiers, int(n), lua_Number(work),
                        lua_Number(kMaxPatternWork));
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// Message handler of the scene's pcall: makes sure the message is a string with a position. Keeps
// the whole message: one with a NUL inside was cut there.
int LuaSandbox::messageHandler(lua_State* L) {
  const char* message = nullptr;
  std::size_t length = 0;
  const int type = lua_type(L, 1);
  if (type == LUA_TSTRING || type == LUA_TNUMBER) {
    message = lua_tolstring(L, 1, &length);
  } else if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) {
    message = lua_tolstring(L, -1, &length);
  } else {
    message = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    length = std::strlen(message);
  }
  if (hasPosition(message)) {
    lua_pushlstring(L, message, length);
  } else {
    lua_pushfstring(L, "%s:%d: ", kChunkToken, currentLine(L));
    lua_pushlstring(L, message, length);
    lua_concat(L, 2);
  }
  return 1;
}

// The scene's xpcall handler, guarded (upvalue 1: the scene's handler). A limit raises its error
// from inside the count hook, and Lua calls the handler before unwinding, with hooks off: a handler
// that looped then ran past every limit (the sandbox audit of 2026-11-28). Once a limit is
// exceeded the error passes on untouched and no scene code runs.
int LuaSandbox::guardedHandler(lua_State* L) {
  if (of(L).exceeded_ != Limit::None) return 1;
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 1);
  return 1;
}

namespace {

// Where xpcall's protected call ends, returning or resumed after a yield: (true, results...) or
// (false, the handler's result). `base` values below the results are the function and handler.
int finishXpcall(lua_State* L, int status, lua_KContext base) {
  if (status != LUA_OK && status != LUA_YIELD) {
    lua_pushboolean(L, 0);
    lua_pushvalue(L, -2);
    return 2;
  }
  return lua_gettop(L) - int(base);
}

}  // namespace

// xpcall(f, handler, ...) with the handler guarded (guardedHandler), by lua_pcallk with a
// continuation as the library's own, so that f may still yield inside a coroutine.
int LuaSandbox::guardedXpcall(lua_State* L) {
  const int n = lua_gettop(L);
  luaL_checktype(L, 2, LUA_TFUNCTION);
  lua_pushvalue(L, 2);
  lua_pushcclosure(L, &LuaSandbox::guardedHandler, 1);
  lua_replace(L, 2);      // [f, guarded handler, args...]
  lua_pushboolean(L, 1);  // the first result on success
  lua_pushvalue(L, 1);    // the function to call
  lua_rotate(L, 3, 2);    // [f, handler, true, f, args...]
  const int status = lua_pcallk(L, n - 2, LUA_MULTRET, 2, 2, finishXpcall);
  return finishXpcall(L, status, 2);
}

// string.rep(s, n, sep) (upvalue 1: the original). An empty s and sep give "" for any n, but the
// library still loops n times, in C where no hook fires: string.rep("", math.maxinteger) ran for
// centuries (the sandbox audit of 2026-11-28). Any other result is allocated whole before the
// loop, so the memory limit bounds it.
int LuaSandbox::boundedRep(lua_State* L) {
  std::size_t length = 0, separator = 0;
  luaL_checklstring(L, 1, &length);
  luaL_checkinteger(L, 2);
  luaL_optlstring(L, 3, "", &separator);
  if (length + separator == 0) {
    lua_pushliteral(L, "");
    return 1;
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 1);
  return 1;
}

// The most elements a table.move, insert or remove may visit: a table within the memory limit
// holds at most maxMemoryBytes / 16 (a Lua value is 16 bytes), so twice that is never a real
// table's. Visiting nils in C allocates nothing and no hook fires: table.move({}, 1, 2^63 - 2, 1,
// {}) ran without end.
std::int64_t LuaSandbox::maxTableSpan() const { return std::int64_t(limits_.maxMemoryBytes / 8); }

// table.move(a1, f, e, t [, a2]) with its element count bounded (upvalue 1: the original).
int LuaSandbox::boundedMove(lua_State* L) {
  const lua_Integer f = luaL_checkinteger(L, 2), e = luaL_checkinteger(L, 3);
  if (e >= f && lua_Unsigned(e) - lua_Unsigned(f) >= lua_Unsigned(of(L).maxTableSpan()))
    return luaL_error(L, "table.move: %I elements from %I to %I, more than a table within the memory limit holds (%I)",
                      lua_Integer(lua_Unsigned(e) - lua_Unsigned(f) + 1), f, e, lua_Integer(of(L).maxTableSpan()));
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// table.insert / table.remove (upvalue 1: the original; upvalue 2: true for insert). A table's own
// length is bounded by the memory limit, but a __len metamethod may claim any length, and the
// shift then loops in C: a claimed 2^63 never ended. With a __len the length is asked once (a
// second ask could answer otherwise), bounded, and the shift done here, as the manual says the
// library does it.
int LuaSandbox::boundedShift(lua_State* L) {
  const bool insert = lua_toboolean(L, lua_upvalueindex(2));
  if (lua_type(L, 1) != LUA_TTABLE || luaL_getmetafield(L, 1, "__len") == LUA_TNIL) {
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
  }
  lua_pop(L, 1);  // the metafield
  const char* name = insert ? "table.insert" : "table.remove";
  const int args = lua_gettop(L);
  const lua_Integer size = luaL_len(L, 1);
  const auto checkSpan = [&](lua_Integer from, lua_Integer to) {
    if (to > from && lua_Unsigned(to) - lua_Unsigned(from) > lua_Unsigned(of(L).maxTableSpan()))
      luaL_error(L, "%s: the table's __len says %I elements, more than a table within the memory limit holds (%I)",
                 name, size, lua_Integer(of(L).maxTableSpan()));
  };
  if (insert) {
    const lua_Integer end = lua_Integer(lua_Unsigned(size) + 1u);  // the first free place
    if (args == 2) {
      lua_seti(L, 1, end);
      return 0;
    }
    if (args != 3) return luaL_error(L, "wrong number of arguments to 'insert'");
    const lua_Integer pos = luaL_checkinteger(L, 2);
    luaL_argcheck(L, lua_Unsigned(pos) - 1u < lua_Unsigned(end), 2, "position out of bounds");
    checkSpan(pos, end);
    for (lua_Integer i = end; i > pos; --i) {
      lua_geti(L, 1, i - 1);
      lua_seti(L, 1, i);
    }
    lua_seti(L, 1, pos);
    return 0;
  }
  lua_Integer pos = luaL_optinteger(L, 2, size);
  if (pos != size) luaL_argcheck(L, lua_Unsigned(pos) - 1u <= lua_Unsigned(size), 2, "position out of bounds");
  checkSpan(pos, size);
  lua_geti(L, 1, pos);  // the result
  for (; pos < size; ++pos) {
    lua_geti(L, 1, pos + 1);
    lua_seti(L, 1, pos);
  }
  lua_pushnil(L);
  lua_seti(L, 1, pos);
  return 1;
}

// print(...): one line "PATH:LINE: v1<TAB>v2..." on stderr, written at once. Quiet (a scene
// evaluated again) it converts its values all the same and writes nothing: a __tostring then runs
// in both evaluations, which a scene could otherwise tell apart (the sandbox audit of 2026-11-28).
int LuaSandbox::print(lua_State* L) {
  // Only Lua values and luaL_Buffer here: a __tostring may raise, a longjmp past C++ objects.
  LuaSandbox& sandbox = of(L);
  const int n = lua_gettop(L);
  // Every value made a string in its own slot first (its __tostring runs here), and only then the
  // buffer: a luaL_Buffer grown past LUAL_BUFFERSIZE (1 KB) keeps a to-be-closed box on the stack,
  // which no lua_insert or lua_remove may move; moving the slots around it made a print longer than
  // 1 KB fail with "attempt to call a nil value" (the hostile-input trial of 2026-11-29).
  for (int i = 1; i <= n; ++i) {
    luaL_tolstring(L, i, nullptr);
    lua_replace(L, i);
  }
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  luaL_addstring(&b, sandbox.scenePath_.c_str());
  lua_pushfstring(L, ":%d: ", currentLine(L));
  luaL_addvalue(&b);
  for (int i = 1; i <= n; ++i) {
    if (i > 1) luaL_addchar(&b, '\t');
    // One line per print: control characters inside a value are written escaped (\n, \r, \x1B,
    // \u{2028}, ...), so that scene output can never look like a line of its own (an error line,
    // say), nor move the terminal's cursor.
    std::size_t length = 0;
    const char* value = lua_tolstring(L, i, &length);  // a string: stays in its slot, below the buffer
    escapeControlsTo(std::string_view(value, length),
                     [&b](const char* piece, std::size_t size) { luaL_addlstring(&b, piece, size); });
  }
  luaL_pushresult(&b);
  std::size_t length = 0;
  const char* text = lua_tolstring(L, -1, &length);
  if (!sandbox.quiet()) note(std::string(text, length));  // stderr's line; sys.stderr in Python (core/warning.h)
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
    lua_pushboolean(L, std::strcmp(name, "gmatch") != 0);  // whether a leading ^ anchors
    lua_pushcclosure(L, &LuaSandbox::boundedPattern, 4);
    lua_setfield(L, -2, name);
  }
  lua_getfield(L, -1, "rep");
  lua_pushcclosure(L, &LuaSandbox::boundedRep, 1);
  lua_setfield(L, -2, "rep");
  lua_pop(L, 1);
  // Library loops that run in C without allocating, bounded (boundedMove, boundedShift).
  lua_getglobal(L, LUA_TABLIBNAME);
  lua_getfield(L, -1, "move");
  lua_pushcclosure(L, &LuaSandbox::boundedMove, 1);
  lua_setfield(L, -2, "move");
  for (const char* name : {"insert", "remove"}) {
    lua_getfield(L, -1, name);
    lua_pushboolean(L, std::strcmp(name, "insert") == 0);
    lua_pushcclosure(L, &LuaSandbox::boundedShift, 2);
    lua_setfield(L, -2, name);
  }
  lua_pop(L, 1);
  lua_pushcfunction(L, &LuaSandbox::guardedXpcall);
  lua_setglobal(L, "xpcall");

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
  return escapeControls(message);
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
  // Handed to the parser one line at a time: an error the parser raises without a position (C
  // stack overflow of deep nesting, too many labels) is at the line it was reading, not at line 1
  // (the sandbox audit of 2026-11-28).
  struct LineReader {
    const std::string& text;
    std::size_t at = 0;
    int lines = 0;  // lines handed out
    static const char* read(lua_State*, void* data, std::size_t* size) {
      auto& r = *static_cast<LineReader*>(data);
      if (r.at >= r.text.size()) {
        *size = 0;
        return nullptr;
      }
      const std::size_t end = std::min(r.text.find('\n', r.at), r.text.size() - 1) + 1;
      const char* piece = r.text.data() + r.at;
      *size = end - r.at;
      r.at = end;
      ++r.lines;
      return piece;
    }
  } reader{source};
  int status = lua_load(L, &LineReader::read, &reader, chunkName.c_str(), "t");
  if (status != LUA_OK) {
    std::size_t length = 0;
    const char* text = lua_type(L, -1) == LUA_TSTRING ? lua_tolstring(L, -1, &length) : nullptr;
    std::string message = text ? std::string(text, length) : "cannot load";
    lua_settop(L, 0);
    // Lua's "'}' expected (to close '{' at line 2) near 'target'" is nearly always a separator
    // forgotten between two fields of a constructor's table (the docs walk of 2026-11-29).
    if (message.find("'}' expected") != std::string::npos && message.find(" near ") != std::string::npos)
      message += " (a missing ',' or ';' between two fields of the table?)";
    throw InputError(formatMessage(message, std::max(1, reader.lines)));
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
  if (status != LUA_OK && lua_type(L, -1) == LUA_TSTRING) {
    std::size_t length = 0;
    const char* text = lua_tolstring(L, -1, &length);
    message.assign(text, length);
  }
  lua_settop(L, 0);
  // A scene that ended in an error of its own reports that error, even past the time: a C++ call
  // that found the time up (pastTimeLimit) says where and why better than "found when it ended".
  if (status == LUA_OK) checkClockAtEnd();

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

// A long library call (a pattern within its bound, a table.move within its span) can pass the time
// limit between two count hooks; a scene that ended just after one was accepted however long it
// took (the sandbox audit of 2026-11-28: 49.7 s against a limit of 5 s). Checked at the end of every
// run and call, the line that of the last hook.
bool LuaSandbox::clockExceeded() {
  if (limits_.maxSeconds > 0 && exceeded_ == Limit::None && elapsedSeconds() > limits_.maxSeconds)
    recordLimit(Limit::Time, lastHookLine_);
  return exceeded_ != Limit::None;
}

void LuaSandbox::checkClockAtEnd() {
  if (exceeded_ == Limit::None && clockExceeded())
    throw InputError(scenePath_ + ":" + std::to_string(exceededLine_) + ": scene exceeded the time limit (" +
                     formatNumber(limits_.maxSeconds) + " s of evaluation, found when it ended; DICSYNTH_SCENE_SECONDS sets another)");
}

void LuaSandbox::callAfterRun(const std::function<void()>& body) {
  std::lock_guard<std::mutex> lock(afterRun_);
  const CLocaleScope cLocale;  // numbers as in the scene's evaluation, whatever the thread's locale
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
  // The scene's function runs under the memory limit even when called from a constructor, whose
  // C++ body allocates unlimited (UnlimitedScope): a Nurbs.deform displacement kept 5.7 GB during
  // the fit (the sandbox audit of 2026-11-28). Inside lua_pcall a refused allocation is the
  // call's error, never a longjmp past the caller's C++ frames.
  const bool unlimited = unlimited_;
  unlimited_ = false;
  const int status = lua_pcall(L, nargs, nresults, base);
  unlimited_ = unlimited;
  lua_remove(L, base);
  if (status == LUA_OK && !clockExceeded()) return;
  std::string message;
  if (status != LUA_OK && lua_type(L, -1) == LUA_TSTRING) {
    std::size_t length = 0;
    const char* text = lua_tolstring(L, -1, &length);
    message.assign(text, length);
  }
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
