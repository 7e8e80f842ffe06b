// core/closest_name.h: the edit distance counts insertions, deletions, substitutions and adjacent
// swaps as one each; a suggestion is within 2 edits, shorter than the word, the first of equals.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "core/closest_name.h"

using namespace dicsynth;

TEST_CASE("closest name: edit distance and the suggestion's bounds") {
  CHECK(editDistance("radius", "radius") == 0);
  CHECK(editDistance("raduis", "radius") == 1);  // adjacent swap
  CHECK(editDistance("--frame", "--frames") == 1);
  CHECK(editDistance("kitten", "sitting") == 3);
  CHECK(editDistance("", "abc") == 3);
  const std::vector<std::string> names = {"render", "compare", "devices", "speckle", "preview", "bench", "sweep"};
  CHECK(closestName("rendr", names) == std::optional<std::string>("render"));
  CHECK(closestName("sweeep", names) == std::optional<std::string>("sweep"));
  CHECK(closestName("cmpare", names) == std::optional<std::string>("compare"));
  CHECK_FALSE(closestName("xyz", names));       // 3 edits or more from every name
  CHECK_FALSE(closestName("b", {"a"}));          // 1 edit, but not shorter than the word
  CHECK(closestName("bx", {"by", "bz"}) == std::optional<std::string>("by"));  // the first of equals
  // Another case, and a beginning (the hostile-input trial of 2026-11-29 got no hint for -D STRAIN
  // nor Camera.Pin).
  CHECK(closestName("STRAIN", {"stress", "strain"}) == std::optional<std::string>("strain"));
  CHECK(closestName("V", {"v", "w"}) == std::optional<std::string>("v"));
  CHECK(closestName("Pin", {"Telecentric", "Pinhole", "ThinLens"}) == std::optional<std::string>("Pinhole"));
  CHECK_FALSE(closestName("Pi", {"Pinhole"}));  // too short to stand for a name
  // A beginning several names have is no hint (a guess misled), and dashes are no letters.
  CHECK_FALSE(closestName("--pre", {"--precision", "--preview"}));
  CHECK_FALSE(closestName("ste", {"step_px", "step_deg"}));
  CHECK_FALSE(closestName("--f", {"--frames", "--seed"}));
}
