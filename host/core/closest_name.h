#pragma once
// "Did you mean ...?" for a mistyped name: a scene's constructor key, a CLI command or option.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dicsynth {

// Optimal string alignment distance (Levenshtein plus adjacent swaps: "raduis" → "radius" is 1).
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate nearest to `word`, when it is within 2 edits and shorter than the word itself (so
// that "x" suggests nothing); the first of equals.
std::optional<std::string> closestName(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace dicsynth
