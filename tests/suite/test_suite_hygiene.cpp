// The suite checks itself: CTest learns the test names from doctest, and CMake splits lists at
// ';', so a TEST_CASE whose name holds a ';' becomes a CTest test that selects no case at all and
// always "passes". This case fails on any such name in tests/.
#include <doctest/doctest.h>

#include <filesystem>
#include <iterator>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

TEST_CASE("suite: no test name contains a semicolon (CTest would run nothing for it)") {
  const std::filesystem::path dir = std::filesystem::path(DS_SOURCE_DIR) / "tests";
  // TEST_CASE( followed by one or more adjacent string literals (names may span lines).
  const std::regex testCase(R"re(TEST_CASE\(((\s*"([^"\\]|\\.)*")+)\s*\))re");
  int names = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
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

TEST_CASE("suite: every test file lives in an area folder, whose name is its cases' CTest label") {
  // tests/<area>/test_*.cpp: CMake labels each case with its folder (cmake/TestLabels.cmake, after
  // every build of the tests), so a file outside a folder would leave its cases unlabelled. Only
  // the doctest main stays in tests/.
  const std::filesystem::path dir = std::filesystem::path(DS_SOURCE_DIR) / "tests";
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".cpp") continue;
    const std::filesystem::path relative = entry.path().lexically_relative(dir);
    if (relative == "test_main.cpp") continue;
    ++files;
    INFO(relative.string());
    CHECK(std::distance(relative.begin(), relative.end()) == 2);  // <area>/<file>
  }
  CHECK(files > 50);
}
