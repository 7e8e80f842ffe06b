#pragma once
// How a value given from outside a scene reaches it: -D name=value, a sweep point's parameter
// (--sweep, or the scene's `sweep` declaration) and Python's defines, one rule on every path
// (docs/sweeps.md, "What the scene receives"), so that `render -D a=V` renders the point a sweep
// renders with a = V (the sweep audit of 2026-11-28 met `-D size=3.0` arriving as the float 3.0,
// the same value of a sweep as the integer 3: "tex_" .. size named two files):
//   - text that Lua reads as a number (decimal, hexadecimal, exponent, spaces around it) is a
//     number; one that is not finite ("1e400") is refused;
//   - a number with an integral value of magnitude up to 2^53, other than −0, is a Lua integer;
//     an integer literal (-D, Python's int) keeps its exact value up to 2^63; any other number is
//     a float;
//   - "true" and "false" are booleans; any other text a string.
// Sweeps hold their numbers as doubles: an integer beyond 2^53 is refused there, not rounded.
#include <optional>
#include <string>

struct lua_State;

namespace dicsynth {

// 2^53: every integer up to it is a double; above it a double is not every integer.
inline constexpr long long kExactInteger = 1LL << 53;
inline constexpr double kExactIntegerLimit = double(kExactInteger);

struct DefineNumber {
  double value = 0;
  bool integerLiteral = false;  // Lua read an integer (its exact value is `integer`)
  long long integer = 0;
};

// Why a sweep, which holds its numbers as doubles, cannot hold `n` exactly, worded to follow the
// value in a message (" is a number that is not finite", ": a sweep holds ..."); "" where it can.
// --sweep values and the scene's declaration refuse by it alike.
std::string sweepNumberProblem(const DefineNumber& n);

// The number Lua reads in `text` (lua_stringtonumber), if the whole text is one.
std::optional<DefineNumber> readDefineNumber(const std::string& text);

// Whether a number arrives as a Lua integer (integral, |v| <= 2^53, not −0).
bool arrivesAsInteger(double v);

// The text of a number that arrives as `v` itself: "3" for an integral value, otherwise the
// shortest text that reads back as the same double, written so that Lua reads a float ("1e+16",
// "-0.0", "0.1").
std::string defineNumberText(double v);

// The usual spelling of the value `text` stands for: "0.5" for "0.50", "16" for "0x10" or "16.0",
// booleans and strings as given. For keys: two texts that give the scene one value give one key.
std::string canonicalDefineText(const std::string& text);

// Pushes the value `text` stands for. False, with nothing pushed, where it is a number that is
// not finite.
bool pushDefineValue(lua_State* L, const std::string& text);

}  // namespace dicsynth
