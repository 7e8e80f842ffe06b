#pragma once
// The points of a sweep: from the scene's global `sweep` or from --sweep options, each point an
// index and the values of the sweep's parameters (set as scene globals, like -D, when it renders).
//
// Index order (stable, documented in docs/sweeps.md):
//  - grid: parameter names sorted by byte order, the LAST name varies fastest (row-major, like
//    nested loops written in name order);
//  - points: as listed;
//  - random: index i = the i-th draw; a parameter's value depends only on (seed, i, its name).
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/sweep_declaration.h"

namespace dicsynth {

struct SweepPoint {
  std::int64_t index = 0;
  SweepAssignment values;  // sorted by name
};

// The command-line form of a declaration. Each --sweep entry is NAME=SPEC with SPEC:
//   A:B:N     N numbers from A to B (linspace, both ends included)
//   V1,V2,... the listed values (a single V is a one-value list)
//   LO:HI     with --random COUNT only: uniform in [LO, HI)
// Several --sweep entries make a grid, or with --random the ranges of one random sweep.
struct SweepOptions {
  std::vector<std::string> sweeps;
  std::optional<std::int64_t> randomCount;  // --random N
  std::uint32_t randomSeed = 1;             // --random-seed S
};

// A sweep's points are generated on demand from the declaration, not listed: a grid or random
// sweep of N points then costs no memory per point (a listed SweepPoint is ~0.2 KB, 2 GB at the
// 10-million-point limit; bench/RESULTS.md, "Sweeps").
struct SweepPlan {
  SweepDeclaration declaration;
  std::vector<std::string> names;  // parameter names, sorted
  std::int64_t count = 0;          // points: indices 0 .. count − 1
  SweepPoint point(std::int64_t index) const;
};

// Parses the --sweep options (Kind::None when there are none). Throws InputError.
SweepDeclaration parseSweepOptions(const SweepOptions& options);

// How many points a declaration has. Throws InputError (too many points, a parameter without values).
std::int64_t sweepPointCount(const SweepDeclaration& declaration);

// Point `index` (0 ≤ index < sweepPointCount) of a declaration.
SweepPoint sweepPoint(const SweepDeclaration& declaration, std::int64_t index);

// Every point of a declaration, in index order. Throws as sweepPointCount.
std::vector<SweepPoint> enumerateSweep(const SweepDeclaration& declaration);

// The sweep of a run: the --sweep options when any are given (they replace the scene's
// declaration), else the scene's global `sweep`, evaluated with `defines` and the sweep's
// parameters unset. Throws InputError when there is neither, or for a bad declaration/option.
SweepPlan planSweep(const std::string& scenePath, const std::vector<std::pair<std::string, std::string>>& defines,
                    const SweepOptions& options);

// The point's values as one line of JSON, {"noise": 1, "strain": 0.01}, in name order: part of the
// point's key (sweep runner), so its text must not change between versions.
std::string parametersJson(const SweepPoint& point);

// "point_00042": the folder of a point under the sweep's output folder (at least 5 digits).
std::string pointFolderName(std::int64_t index);

// The -D defines of one point: `defines` followed by the point's values.
std::vector<std::pair<std::string, std::string>> pointDefines(
    const std::vector<std::pair<std::string, std::string>>& defines, const SweepPoint& point);

// Uniform number in [0, 1) with 53 random bits, a pure function of (seed, index, name)
// (shaders/shared/rng.h's ds_hash; never std:: distributions).
double sweepUniform(std::uint32_t seed, std::int64_t index, const std::string& name);

}  // namespace dicsynth
