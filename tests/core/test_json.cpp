// core/json.h: a document nested deeper than jsoncpp's stack limit is no document, as any damage is,
// not an exception: a point.json or calibration cache of 100000 '[' ended every sweep or render that
// read it with "Exceeded stackLimit in readValue()" (the hostile-input trial of 2026-11-29).
#include <doctest/doctest.h>

#include <string>

#include "core/json.h"
#include "temp_folder.h"

using namespace dicsynth;

TEST_CASE("json: a document nested too deep is none, not an exception") {
  for (const std::size_t depth : {std::size_t(5000), std::size_t(100000)}) {
    CAPTURE(depth);
    const std::string deep(depth, '[');
    std::optional<Json::Value> parsed;
    CHECK_NOTHROW(parsed = json::parse(deep));
    CHECK_FALSE(parsed.has_value());
    CHECK_FALSE(json::parse(deep + std::string(depth, ']')).has_value());
    test::TempFolder dir;
    CHECK_FALSE(json::readFile(dir.write("point.json", deep)).has_value());
  }
  // Nesting a document of ours could hold still reads.
  const std::string shallow = std::string(50, '[') + "1" + std::string(50, ']');
  CHECK(json::parse(shallow).has_value());
}
