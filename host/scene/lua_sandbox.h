#pragma once
// LuaSandbox: one Lua 5.4 state that runs one scene file, with only the harmless libraries, an
// instruction limit and a memory limit, and errors turned into ONE line "FILE:LINE: message".
//
// What a scene can use: the base library without dofile/loadfile/load/require/collectgarbage,
// and table, string (without string.dump), math, utf8, coroutine. io, os, package and debug are
// never opened. Chunks load in text mode only. `print` writes "FILE:LINE: ..." to stderr.
// math.random is seeded with a fixed value (kRandomSeed), so the same scene draws the same
// numbers on every run; a scene may reseed it, e.g. math.randomseed(frame).
// setmetatable refuses metatables with a __gc field: Lua runs finalizers with hooks off, so a
// finalizer would escape the instruction limit.
//
// Limits (see SceneParams in scene.h for the defaults and why):
//  - instructions: a count hook fires every kHookInterval VM instructions and raises
//    "scene exceeded the instruction limit (N instructions)" once the total passes the limit;
//  - memory: the allocator refuses growth beyond the limit; Lua then raises a memory error (its
//    message handler is not called for those, so the allocator records the line itself; exact up
//    to Lua 5.4.4, approximate on later versions, see allocate());
//  - time: the count hook also compares the wall-clock time since the run started with the limit,
//    which bounds loops of calls that are one instruction each but long (string.format,
//    table.concat: each also bounded by the memory limit, which caps its result); the clock is
//    read again when a run or call ends, so a long last call cannot pass unseen;
//  - library loops in C that allocate nothing are bounded: string.rep of an empty string and
//    separator returns "" at once, table.move visits, and table.insert/remove shift, at most
//    maxMemoryBytes / 8 elements (more than a table within the limit holds);
//  - pattern work: string.find, match, gmatch and gsub are wrapped: a pattern with q quantifiers
//    (* + - ?, and each %b and back-reference %1..%9) can take ~n^(q+1) steps on a subject of n
//    characters (n^q when anchored with ^, which gmatch does not do), inside one C call that no
//    hook interrupts, so a call whose bound exceeds kMaxPatternWork is refused with an error at
//    its line. A plain find (4th argument true) is linear and never refused;
//  - xpcall's handler is not called once a limit is exceeded (the limit raises inside the hook,
//    where Lua runs the handler with hooks off).
// Both are sticky: once exceeded, the hook raises at every instruction, so a scene's pcall cannot
// swallow the error and carry on, and the load fails even if the scene caught the error.
//
// Error safety: Lua errors are longjmps, which must not cross C++ frames holding objects with
// destructors. C functions written in C++ therefore go through protectedCall() (lua_values.h):
// their C++ body runs inside an UnlimitedScope (no allocation is refused, so the Lua API calls
// they make cannot raise), uses raw table access only (no metamethods, so no scene code runs),
// reports problems by throwing, and the Lua error is raised after every C++ object is gone.
#include <cstddef>
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "core/error.h"

struct lua_State;
struct lua_Debug;

namespace dicsynth::scene {

struct SandboxLimits {
  std::uint64_t maxInstructions = 0;
  std::size_t maxMemoryBytes = 0;
  double maxSeconds = 0;  // wall-clock time of one run (or one callAfterRun); 0: none
  bool quiet = false;     // print writes nothing (a scene evaluated again, whose output was seen)
};

// The chunk name under which the scene runs. Lua's own messages then read "<scene>:12: ...";
// the sandbox replaces the token by the scene path as given (Lua would shorten long paths).
inline constexpr const char* kChunkToken = "<scene>";
inline constexpr int kHookInterval = 1000;  // VM instructions between two count-hook calls
inline constexpr std::int64_t kRandomSeed = 20240101;
inline constexpr double kMaxPatternWork = 1e9;  // steps (see the header comment): ~1 s at most

// `text` with its control characters escaped, so that it stays one line that cannot move a
// terminal's cursor: "\n", "\r", other C0 controls and DEL as "\xHH" (tab kept), NEL, LINE and
// PARAGRAPH SEPARATOR (U+0085, U+2028, U+2029) as "\u{85}", ... Pieces go to append(ptr, length).
template <class Append>
void escapeControlsTo(std::string_view text, Append&& append) {
  static const char* const kHex = "0123456789ABCDEF";
  std::size_t plain = 0;  // start of the run of characters copied as they are
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const auto next = [&](std::size_t k) { return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0; };
    char escaped[12] = {};
    std::size_t used = 0;  // bytes of the input the escape stands for
    if (c == '\n') {
      std::memcpy(escaped, "\\n", 2), used = 1;
    } else if (c == '\r') {
      std::memcpy(escaped, "\\r", 2), used = 1;
    } else if ((c < 0x20 && c != '\t') || c == 0x7f) {
      escaped[0] = '\\', escaped[1] = 'x', escaped[2] = kHex[c >> 4], escaped[3] = kHex[c & 15], used = 1;
    } else if (c == 0xC2 && next(1) == 0x85) {
      std::memcpy(escaped, "\\u{85}", 6), used = 2;
    } else if (c == 0xE2 && next(1) == 0x80 && (next(2) == 0xA8 || next(2) == 0xA9)) {
      std::memcpy(escaped, next(2) == 0xA8 ? "\\u{2028}" : "\\u{2029}", 8), used = 3;
    }
    if (used == 0) continue;
    append(text.data() + plain, i - plain);
    append(escaped, std::strlen(escaped));
    i += used - 1;
    plain = i + 1;
  }
  append(text.data() + plain, text.size() - plain);
}
std::string escapeControls(std::string_view text);

// Shortest text that reads back as the same double ("0.1", "-3", "inf", "nan"), for messages.
std::string formatNumber(double value);

// Made by std::make_shared when values of the scene call back into Lua after the run (a
// Nurbs.deform field): they hold a weak_ptr and the Scene the owning pointer (Scene::keepAlive).
class LuaSandbox : public std::enable_shared_from_this<LuaSandbox> {
 public:
  LuaSandbox(std::string scenePath, SandboxLimits limits);
  ~LuaSandbox();
  LuaSandbox(const LuaSandbox&) = delete;
  LuaSandbox& operator=(const LuaSandbox&) = delete;

  lua_State* state() const { return L_; }
  // The NURBS control points the scene's constructors made so far, `n` more included.
  std::uint64_t addNurbsControlPoints(std::uint64_t n) { return nurbsControlPoints_ += n; }
  bool quiet() const { return limits_.quiet; }  // SandboxLimits::quiet: constructors report nothing either
  const std::string& scenePath() const { return scenePath_; }          // as given by the user
  // What determines this evaluation's values: the scene's path and text, the frame and the defines
  // (set by loadScene; a scene is deterministic). Evaluating the same again gives the same scene,
  // so a Nurbs.deform fit remembered from it is this evaluation's own, not one reused.
  const std::string& evaluation() const { return evaluation_; }
  // Whether the run (or callAfterRun) has taken longer than its time limit, for C++ work the count
  // hook cannot interrupt (a Nurbs.deform fit of a mesh field ran 493 s against a 60 s limit and was
  // then refused "at line 0": the FE trial of 2026-11-29). Records nothing: the caller throws its own
  // error, which the scene's end reports as it is.
  bool pastTimeLimit() const { return limits_.maxSeconds > 0 && elapsedSeconds() > limits_.maxSeconds; }
  double timeLimitSeconds() const { return limits_.maxSeconds; }
  void setEvaluation(std::string evaluation) { evaluation_ = std::move(evaluation); }
  const std::filesystem::path& sceneDir() const { return sceneDir_; }  // folder of the scene file

  // Loads `source` (text only) as the scene's main chunk and runs it under the limits.
  // Throws InputError("PATH:LINE: message") on a syntax error, a runtime error or a limit.
  void run(const std::string& source);

  // After run(): runs `body`, which calls into the state with call(), under fresh limits (the same
  // instruction and memory limits as the scene, counted from zero for this body). Serialized:
  // safe from any thread. Throws what body throws, or InputError for a limit.
  void callAfterRun(const std::function<void()>& body);
  // lua_pcall of the function and nargs arguments on the stack, with the scene's message handler,
  // from a C function while the scene runs or inside callAfterRun's body. On error pops what it
  // pushed and throws InputError("PATH:LINE: message") (during run(), run() then reports a limit
  // the scene ran into in its own words).
  void call(int nargs, int nresults);

  // The sandbox owning L (L may be any thread of the state).
  static LuaSandbox& of(lua_State* L);
  // Line of the innermost active Lua function of L (0 if there is none).
  static int currentLine(lua_State* L);
  // SourceLoc of the Lua code that is running on L: the scene path and currentLine(L).
  SourceLoc here(lua_State* L) const { return SourceLoc{scenePath_, currentLine(L)}; }

  // While alive, the allocator refuses nothing (see the header comment). Nests.
  class UnlimitedScope {
   public:
    explicit UnlimitedScope(lua_State* L);
    ~UnlimitedScope();
    UnlimitedScope(const UnlimitedScope&) = delete;
    UnlimitedScope& operator=(const UnlimitedScope&) = delete;

   private:
    LuaSandbox& sandbox_;
    bool previous_;
  };

  // While alive, the instructions counted are this scope's alone and do not count towards the
  // enclosing run's or batch's: each call of a Nurbs.deform displacement function gets the whole
  // instruction limit for itself (a runaway function still stops), while a fit's millions of calls
  // no longer exhaust the scene's budget (the deformation audit of 2026-11-28: a mild sinusoid at
  // tol 1e-9 stopped with "scene exceeded the instruction limit"). `what` names the call in the
  // limit's message ("one call of the Nurbs.deform displacement").
  class OwnInstructionBudget {
   public:
    OwnInstructionBudget(LuaSandbox& sandbox, const char* what);
    ~OwnInstructionBudget();
    OwnInstructionBudget(const OwnInstructionBudget&) = delete;
    OwnInstructionBudget& operator=(const OwnInstructionBudget&) = delete;

   private:
    LuaSandbox& sandbox_;
    std::uint64_t saved_;
    const char* savedWhat_;
  };

 private:
  enum class Limit { None, Instructions, Memory, Time };

  static void* allocate(void* ud, void* ptr, std::size_t oldSize, std::size_t newSize);
  static void countHook(lua_State* L, lua_Debug* ar);
  static int messageHandler(lua_State* L);
  static int print(lua_State* L);
  static int setmetatableNoGc(lua_State* L);
  static int boundedPattern(lua_State* L);
  static int guardedHandler(lua_State* L);
  static int guardedXpcall(lua_State* L);
  static int boundedRep(lua_State* L);
  static int boundedMove(lua_State* L);
  static int boundedShift(lua_State* L);
  std::int64_t maxTableSpan() const;
  void startClock();
  double elapsedSeconds() const;
  bool clockExceeded();    // records Limit::Time when the run's time is up; whether a limit was exceeded
  void checkClockAtEnd();  // throws the time limit's InputError when clockExceeded() finds it now

  void openLibraries();
  void recordLimit(Limit which, int line);
  // "<scene>:12: msg" → "PATH:12: msg", on one line; adds PATH:fallbackLine when no position.
  std::string formatMessage(const std::string& luaMessage, int fallbackLine) const;

  std::string scenePath_;
  std::string evaluation_;
  std::filesystem::path sceneDir_;
  SandboxLimits limits_;
  lua_State* L_ = nullptr;

  // Allocator and hook state.
  std::size_t bytesInUse_ = 0;
  bool enforceMemory_ = false;  // only while the scene runs
  bool unlimited_ = false;      // UnlimitedScope
  std::uint64_t instructions_ = 0;
  std::int64_t startNanoseconds_ = 0;  // steady clock at the start of the run
  std::mutex afterRun_;  // callAfterRun
  Limit exceeded_ = Limit::None;  // first limit the scene ran into
  int exceededLine_ = 0;
  const char* budget_ = nullptr;          // OwnInstructionBudget's `what` while one is alive
  const char* exceededBudget_ = nullptr;  // budget_ when the instruction limit was exceeded
  std::uint64_t nurbsControlPoints_ = 0;  // addNurbsControlPoints
  int lastHookLine_ = 0;  // line at the last count hook (the allocator's on newer Lua; the clock's at the end)
};

}  // namespace dicsynth::scene
