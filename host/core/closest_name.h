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

// The candidate equal to `word` but for case; else the one candidate that begins with it (in any
// case, a word of 3 letters or digits or more; none where several do); else the nearest within 2
// edits and fewer edits than the word's length (so that "x" suggests nothing), the first of equals.
std::optional<std::string> closestName(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace dicsynth
