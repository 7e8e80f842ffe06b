#include "sweep/sweep_points.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/json.h"
#include "scene/define_value.h"
#include "scene/scene.h"
#include "shared/rng.h"

namespace dicsynth {
namespace {

bool isIdentifier(const std::string& name) {
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (name.empty() || !letter(name[0])) return false;
  return std::all_of(name.begin(), name.end(), [&](char c) { return letter(c) || (c >= '0' && c <= '9'); });
}

// A number of --sweep as Lua reads it, with -D's rule (scene/define_value.h): nullopt for text
// that is no number; a number the sweep cannot hold exactly (not finite, an integer beyond 2^53)
// is refused, `option` naming the entry.
std::optional<double> parseNumber(const std::string& text, const std::string& option) {
  const auto n = readDefineNumber(text);
  if (!n) return std::nullopt;
  if (const std::string problem = sweepNumberProblem(*n); !problem.empty())
    throw InputError(option + "'" + text + "'" + problem);
  return n->value;
}

SweepValue parseValue(const std::string& text, const std::string& option) {
  if (auto n = parseNumber(text, option)) return SweepValue::ofNumber(*n);
  if (text == "true" || text == "false") return {SweepValue::Kind::Boolean, 0, text == "true", {}};
  return {SweepValue::Kind::String, 0, false, text};
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const auto end = text.find(sep, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

}  // namespace

double sweepUniform(std::uint32_t seed, std::int64_t index, const std::string& name) {
  // The name enters as a hash of its bytes, so adding a parameter changes no other one's draws.
  uint nameKey = ds_hash(uint(name.size()) ^ 0x6a09e667u);
  for (unsigned char c : name) nameKey = ds_hash_combine(nameKey, c);
  const auto i = std::uint64_t(index);
  uint h = ds_hash(seed ^ 0x9e3779b9u);
  h = ds_hash_combine(h, uint(i & 0xffffffffu));
  h = ds_hash_combine(h, uint(i >> 32));
  h = ds_hash_combine(h, nameKey);
  const uint a = ds_hash_combine(h, 1u), b = ds_hash_combine(h, 2u);
  // 26 + 27 = 53 bits: every double in [0, 1) on the 2^-53 grid is equally likely.
  return (double(a >> 6) * 134217728.0 + double(b >> 5)) * 0x1p-53;
}

SweepDeclaration parseSweepOptions(const SweepOptions& options) {
  SweepDeclaration d;
  if (options.sweeps.empty()) {
    if (options.randomCount) throw InputError("--random: give the ranges with --sweep NAME=LO:HI");
    return d;
  }
  d.origin = "--sweep";
  d.kind = options.randomCount ? SweepDeclaration::Kind::Random : SweepDeclaration::Kind::Grid;
  if (options.randomCount) {
    if (*options.randomCount < 1 || *options.randomCount > kMaxSweepPoints)
      throw InputError("--random " + std::to_string(*options.randomCount) + ": the number of points must be in 1.." +
                       std::to_string(kMaxSweepPoints));
    d.count = *options.randomCount;
    d.seed = options.randomSeed;
  }
  for (const std::string& entry : options.sweeps) {
    const std::string option = "--sweep " + entry + ": ";
    const auto eq = entry.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError(option + "expected NAME=A:B:N, NAME=V1,V2,... or NAME=LO:HI");
    const std::string name = entry.substr(0, eq), spec = entry.substr(eq + 1);
    const auto colons = split(spec, ':');
    if (d.kind == SweepDeclaration::Kind::Random) {
      const auto lo = colons.size() == 2 ? parseNumber(colons[0], option) : std::nullopt;
      const auto hi = colons.size() == 2 ? parseNumber(colons[1], option) : std::nullopt;
      if (!lo || !hi) throw InputError(option + "with --random, expected NAME=LO:HI (numbers)");
      if (!(*lo < *hi)) throw InputError(option + "empty range (LO must be < HI)");
      // lo + (hi − lo)·u with hi − lo infinite gave every point the same value (the sweep audit:
      // -1e308:1e308, five points of 9.9999999999999981e+307).
      if (!std::isfinite(*hi - *lo))
        throw InputError(option + "HI - LO overflows a double: a range this wide cannot be drawn uniformly");
      d.ranges.push_back({name, *lo, *hi});
      continue;
    }
    SweepAxis axis{name, {}};
    if (colons.size() == 3) {
      const auto a = parseNumber(colons[0], option), b = parseNumber(colons[1], option);
      long long n = 0;
      const auto r = std::from_chars(colons[2].data(), colons[2].data() + colons[2].size(), n);
      const auto count = readDefineNumber(colons[2]);  // "1e20": too many, not "no integer"
      if (a && b && count && count->value > double(kMaxSweepPoints) && count->value == std::floor(count->value))
        throw InputError(option + "N is more than " + std::to_string(kMaxSweepPoints));
      if (!a || !b || r.ec != std::errc() || r.ptr != colons[2].data() + colons[2].size())
        throw InputError(option + "expected A:B:N (numbers A, B and an integer N)");
      if (n < 1) throw InputError(option + "N = " + std::to_string(n) + " gives an empty range (N must be >= 1)");
      if (n > kMaxSweepPoints) throw InputError(option + "N is more than " + std::to_string(kMaxSweepPoints));
      axis.a = *a;
      axis.b = *b;
      axis.spaced = n;  // made on demand (SweepAxis)
    } else if (colons.size() == 1) {
      for (const std::string& v : split(spec, ',')) {
        if (v.empty()) throw InputError(option + "empty value in the list (write V1,V2,...)");
        axis.values.push_back(parseValue(v, option));
      }
    } else {
      throw InputError(option + "expected A:B:N or V1,V2,... (LO:HI needs --random COUNT)");
    }
    d.grid.push_back(std::move(axis));
  }
  std::sort(d.grid.begin(), d.grid.end(), [](const auto& x, const auto& y) { return x.name < y.name; });
  std::sort(d.ranges.begin(), d.ranges.end(), [](const auto& x, const auto& y) { return x.name < y.name; });
  return d;
}

std::int64_t sweepPointCount(const SweepDeclaration& d) {
  switch (d.kind) {
    case SweepDeclaration::Kind::None: return 0;
    case SweepDeclaration::Kind::Grid: {
      std::int64_t total = 1;
      for (const SweepAxis& axis : d.grid) {
        if (axis.size() == 0) throw InputError(d.origin + ": sweep parameter '" + axis.name + "' has no value");
        if (total > kMaxSweepPoints / axis.size())
          throw InputError(d.origin + ": the grid has more than " + std::to_string(kMaxSweepPoints) + " points");
        total *= axis.size();
      }
      return total;
    }
    case SweepDeclaration::Kind::Points: return std::int64_t(d.points.size());
    case SweepDeclaration::Kind::Random: return d.count;
  }
  return 0;
}

SweepPoint sweepPoint(const SweepDeclaration& d, std::int64_t i) {
  SweepPoint p{i, {}};
  switch (d.kind) {
    case SweepDeclaration::Kind::None: break;
    case SweepDeclaration::Kind::Grid: {
      p.values.resize(d.grid.size());
      std::int64_t rest = i;
      for (std::size_t k = d.grid.size(); k-- > 0;) {  // the last name varies fastest
        const SweepAxis& axis = d.grid[k];
        p.values[k] = {axis.name, axis.at(rest % axis.size())};
        rest /= axis.size();
      }
      break;
    }
    case SweepDeclaration::Kind::Points: p.values = d.points.at(std::size_t(i)); break;
    case SweepDeclaration::Kind::Random:
      for (const SweepRange& r : d.ranges) {
        double x = r.lo + (r.hi - r.lo) * sweepUniform(d.seed, i, r.name);
        if (x >= r.hi) x = std::nextafter(r.hi, r.lo);  // rounding must not reach the open end
        p.values.emplace_back(r.name, SweepValue::ofNumber(x));
      }
      break;
  }
  return p;
}

std::vector<SweepPoint> enumerateSweep(const SweepDeclaration& d) {
  const std::int64_t n = sweepPointCount(d);
  std::vector<SweepPoint> points;
  points.reserve(std::size_t(n));
  for (std::int64_t i = 0; i < n; ++i) points.push_back(sweepPoint(d, i));
  return points;
}

SweepPoint SweepPlan::point(std::int64_t index) const { return sweepPoint(declaration, index); }

SweepPlan planSweep(const std::string& scenePath, const std::vector<std::pair<std::string, std::string>>& defines,
                    const SweepOptions& options) {
  SweepPlan plan;
  plan.declaration = parseSweepOptions(options);
  if (plan.declaration.kind == SweepDeclaration::Kind::None) {
    plan.declaration = loadSweepDeclaration(scenePath, SceneParams{defines, 0});
    if (plan.declaration.kind == SweepDeclaration::Kind::None)
      throw InputError(scenePath + ": the scene declares no sweep (global `sweep`) and no --sweep option is given");
  }
  plan.count = sweepPointCount(plan.declaration);
  if (plan.count == 0) throw InputError(plan.declaration.origin + ": the sweep has no point");
  for (const auto& [name, value] : plan.point(0).values) plan.names.push_back(name);
  for (const std::string& name : plan.names) {
    const std::string what = plan.declaration.origin + ": sweep parameter '" + name + "': ";
    if (!isIdentifier(name)) throw InputError(what + "not a Lua identifier (letters, digits and _, not starting with a digit)");
    if (name == "frame") throw InputError(what + "'frame' is reserved (use --frames)");
    if (isSceneLanguageName(name))
      throw InputError(what + "a built-in name of the scene language (like Shape, linspace, _G, string): choose another name");
    for (const auto& define : defines)
      if (define.first == name) throw InputError(what + "also given by -D " + name + "; give it in one place");
    if (std::count(plan.names.begin(), plan.names.end(), name) > 1)
      throw InputError(what + "given twice; give each parameter once (a grid's values in one --sweep)");
  }
  return plan;
}

std::string parametersJson(const SweepPoint& point) {
  std::string s = "{";
  for (std::size_t i = 0; i < point.values.size(); ++i)
    s += (i ? ", " : "") + json::quote(point.values[i].first) + ": " + point.values[i].second.json();
  return s + "}";
}

std::string pointFolderName(std::int64_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "point_%05lld", static_cast<long long>(index));
  return buf;
}

std::vector<std::pair<std::string, std::string>> pointDefines(
    const std::vector<std::pair<std::string, std::string>>& defines, const SweepPoint& point) {
  auto out = defines;
  for (const auto& [name, value] : point.values) out.emplace_back(name, value.defineText());
  return out;
}

}  // namespace dicsynth
