// The suite checks itself: CTest learns the test names from doctest, and CMake splits lists at
// ';', so a TEST_CASE whose name holds a ';' becomes a CTest test that selects no case at all and
// always "passes". This case fails on any such name in tests/.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

TEST_CASE("suite: no test name contains a semicolon (CTest would run nothing for it)") {
  const std::filesystem::path dir = std::filesystem::path(DS_SOURCE_DIR) / "tests";
  // TEST_CASE( followed by one or more adjacent string literals (names may span lines).
  const std::regex testCase(R"re(TEST_CASE\(((\s*"([^"\\]|\\.)*")+)\s*\))re");
  int names = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".cpp") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    const std::string source = text.str();
    for (std::sregex_iterator it(source.begin(), source.end(), testCase), end; it != end; ++it) {
      ++names;
      INFO(entry.path().filename().string() << ": " << (*it)[1].str());
      CHECK((*it)[1].str().find(';') == std::string::npos);
    }
  }
  CHECK(names > 100);  // the scan found the suite (this file's own name has no semicolon)
}
