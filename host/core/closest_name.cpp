#include "core/closest_name.h"

#include <algorithm>
#include <cctype>

namespace dicsynth {

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

namespace {

bool sameIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

std::optional<std::string> closestName(std::string_view word, const std::vector<std::string>& candidates) {
  // The same name in other case first ("-D STRAIN" for `strain`), then a name the word begins, of
  // 3 letters or more ("Camera.Pin" for Pinhole): edits counted neither (the hostile-input trial of
  // 2026-11-29 got no hint for either).
  for (const std::string& candidate : candidates)
    if (sameIgnoringCase(word, candidate)) return candidate;
  // Letters and digits counted ("--f" is one letter, too little to stand for a name), and only a
  // beginning that one candidate has: "--pre" is --precision's and --preview's, "ste" step_px's and
  // step_deg's (a guess between them misled: the hostile-input trial of 2026-11-29).
  const auto letters = std::count_if(word.begin(), word.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
  if (letters >= 3) {
    std::optional<std::string> prefixed;
    int matches = 0;
    for (const std::string& candidate : candidates)
      if (candidate.size() > word.size() && sameIgnoringCase(word, std::string_view(candidate).substr(0, word.size()))) {
        ++matches;
        prefixed = candidate;
      }
    if (matches == 1) return prefixed;
  }
  std::optional<std::string> best;
  std::size_t bestDistance = 3;
  for (const std::string& candidate : candidates) {
    // The distance is at least the difference in length: a word far longer than every candidate
    // costs nothing (a 100 MB key of a scene took gigabytes of table: the sandbox audit of 2026-11-28).
    const std::size_t lengthGap = word.size() > candidate.size() ? word.size() - candidate.size() : candidate.size() - word.size();
    if (lengthGap >= bestDistance) continue;
    const std::size_t distance = editDistance(word, candidate);
    if (distance < bestDistance && distance < word.size()) {
      best = candidate;
      bestDistance = distance;
    }
  }
  return best;
}

}  // namespace dicsynth
