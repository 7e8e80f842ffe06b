// The manual's snippets are executed (a doc test), so that README.md and docs/*.md cannot drift
// from the program. Each fenced block, by its info string:
//   ```lua           a scene: rendered by the CLI (CPU reference, 1/16 of the resolution, 1 sample),
//                    with a default camera added when the block has none; it must succeed;
//   ```lua fragment  a part of a scene that needs more around it: compiled by Lua only;
//   ```sh            each command line starting with build/dicsynth or PYTHONPATH=build runs from a
//                    temporary folder where build/, scenes/, examples/ and bench/ are the
//                    repository's; render, sweep and compare get --downscale 16 --spp 1 unless the
//                    line sets them; it must exit 0. Lines starting with ./scripts/ are the quick
//                    start, which CI itself runs (.ci/run); comments and blank lines are skipped;
//   ```sh cluster    needs Slurm or GNU parallel: not run here (tests/sweep/test_slurm_scripts.cpp runs
//                    the Slurm scripts with bash);
//   ```sh slow       run only with DICSYNTH_DOC_SLOW=1 (minutes of rendering);
//   other blocks (python, plain text) are not executed (the Python examples run in tests/python).
#include <doctest/doctest.h>

#include <lua.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "model/layers.h"
#include "cameras/registry.h"
#include "reflectance/registry.h"
#include "shapes/registry.h"
#include "textures/registry.h"
#include "run_cli.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

struct Block {
  std::string file;
  int line = 0;      // of the opening fence
  std::string info;  // "lua", "lua fragment", "sh", ...
  std::string text;
};

std::vector<Block> blocks() {
  std::vector<std::filesystem::path> files = {std::filesystem::path(DS_SOURCE_DIR) / "README.md"};
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(DS_SOURCE_DIR) / "docs"))
    if (e.path().extension() == ".md") files.push_back(e.path());
  std::sort(files.begin() + 1, files.end());
  std::vector<Block> out;
  for (const auto& path : files) {
    std::ifstream in(path);
    std::string line;
    int number = 0;
    Block* open = nullptr;
    while (std::getline(in, line)) {
      ++number;
      if (line.rfind("```", 0) == 0) {
        if (open) {
          open = nullptr;
        } else {
          out.push_back({path.filename().string(), number, line.substr(3), ""});
          open = &out.back();
        }
        continue;
      }
      if (open) open->text += line + "\n";
    }
  }
  return out;
}

// A page of docs/, whole.
std::string docText(const char* name) { return test::readBytes(std::string(DS_SOURCE_DIR) + "/docs/" + name); }

// The line of `text` that starts with `prefix` (a table row).
std::string tableRow(const std::string& text, const std::string& prefix) {
  const std::size_t start = text.find(prefix);
  REQUIRE(start != std::string::npos);
  return text.substr(start, text.find('\n', start) - start);
}

// A scene-language row names `constructor` (in backticks) and each of `keys`.
template <class Keys>
void checkConstructorRow(const std::string& row, const std::string& constructor, const Keys& keys) {
  INFO(constructor);
  CHECK(row.find("`" + constructor + "`") != std::string::npos);
  for (const char* key : keys) {
    INFO(key);
    CHECK(row.find(key) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("docs: every lua and sh snippet of README.md and docs/ runs") {
  const std::vector<Block> all = blocks();
  const bool slow = std::getenv("DICSYNTH_DOC_SLOW") != nullptr;
  std::size_t scenes = 0, fragments = 0, commands = 0;
  for (const Block& b : all) {
    const std::string where = b.file + ":" + std::to_string(b.line);
    INFO(where << " ```" << b.info << "\n" << b.text);
    if (b.info == "lua fragment") {
      lua_State* L = luaL_newstate();
      const int status = luaL_loadbufferx(L, b.text.data(), b.text.size(), where.c_str(), "t");
      CHECK_MESSAGE(status == LUA_OK, (lua_tostring(L, -1) ? lua_tostring(L, -1) : ""));
      lua_close(L);
      ++fragments;
    } else if (b.info == "lua") {
      test::TempFolder dir;
      std::filesystem::create_symlink(std::filesystem::path(DS_SOURCE_DIR) / "scenes" / "speckle.tif", dir.path() / "speckle.tif");
      const bool camera = b.text.find("Camera.") != std::string::npos;
      const std::string scene = dir.write(
          "snippet.lua", (camera ? "" : "docCamera = Camera.Pinhole { resolution = {320, 240}; focalLength = 0.016; "
                                        "pixelSize = {1e-5, 1e-5}; position = {0, 0, 0} }\n") + b.text);
      const test::CliResult r =
          test::runCli("render " + scene + " -o " + dir.file("out") + " --backend cpu --downscale 16 --spp 1 --layers image");
      INFO(r.err);
      CHECK(r.exitCode == 0);
      ++scenes;
    } else if (b.info == "sh" || (b.info == "sh slow" && slow)) {
      test::TempFolder dir;
      for (const char* link : {"build", "scenes", "examples", "bench"}) {
        const std::filesystem::path target =
            std::string(link) == "build" ? std::filesystem::path(DS_BINARY).parent_path() : std::filesystem::path(DS_SOURCE_DIR) / link;
        std::filesystem::create_directory_symlink(target, dir.path() / link);
      }
      std::istringstream lines(b.text);
      for (std::string line; std::getline(lines, line);) {
        if (const auto hash = line.find("  #"); hash != std::string::npos) line = line.substr(0, hash);  // a trailing comment
        while (!line.empty() && line.back() == ' ') line.pop_back();
        if (line.empty() || line[0] == '#' || line.rfind("./scripts/", 0) == 0) continue;
        REQUIRE_MESSAGE((line.rfind("build/dicsynth ", 0) == 0 || line.rfind("PYTHONPATH=build ", 0) == 0),
                        where << ": a shell line the doc test cannot run: " << line);
        for (const char* sub : {"build/dicsynth render ", "build/dicsynth sweep ", "build/dicsynth compare "})
          if (line.rfind(sub, 0) == 0) {
            if (line.find("--downscale ") == std::string::npos) line += " --downscale 16";
            if (line.find("--spp ") == std::string::npos) line += " --spp 1";
          }
        const std::string command = "cd " + dir.path().string() + " && " + line + " > " + dir.file("stdout.txt") +
                                    " 2> " + dir.file("stderr.txt");
        const int status = std::system(command.c_str());
        INFO(line << "\nstderr: " << test::readBytes(dir.file("stderr.txt")));
        CHECK(status == 0);
        ++commands;
      }
    }
  }
  MESSAGE(scenes << " scene snippets rendered, " << fragments << " fragments compiled, " << commands << " commands run");
  CHECK(scenes >= 4);
  CHECK(commands >= 6);
}

TEST_CASE("docs: the output-layer table of docs/outputs.md is the layer schema's") {
  // docs/outputs.md lists each --layers name with its file or channels ("P.X/Y/Z" stands for P.X,
  // P.Y, P.Z); the program's schema is model/layers.cpp. Same names in the same order, the same
  // channels per layer in file order.
  std::ifstream in(std::string(DS_SOURCE_DIR) + "/docs/outputs.md");
  REQUIRE(in);
  std::vector<std::pair<std::string, std::vector<std::string>>> rows;
  std::vector<std::string> comparisons;  // the last column
  bool inTable = false;
  for (std::string line; std::getline(in, line);) {
    if (line == "| layer | file or channels | can be produced | GPU against CPU (`compare`) |") inTable = true;
    if (!inTable) continue;
    if (line.rfind("|", 0) != 0) break;  // the table's end
    if (line.rfind("| `", 0) != 0) continue;
    const auto nameEnd = line.find("` |", 3);
    if (nameEnd == std::string::npos) continue;
    const std::string name = line.substr(3, nameEnd - 3);
    const auto cellEnd = line.find(" |", nameEnd + 3);
    const std::string cell = line.substr(nameEnd + 4, cellEnd - nameEnd - 4);
    std::vector<std::string> channels;
    for (std::size_t at = cell.find('`'); at != std::string::npos;) {
      const std::size_t close = cell.find('`', at + 1);
      REQUIRE(close != std::string::npos);  // balanced backticks
      const std::string token = cell.substr(at + 1, close - at - 1);
      at = cell.find('`', close + 1);
      const auto dot = token.find('.'), slash = token.find('/');
      if (dot != std::string::npos && slash != std::string::npos && token.find(".tif") == std::string::npos) {
        // "P.X/Y/Z": the prefix with each suffix
        const std::string prefix = token.substr(0, dot + 1);
        std::stringstream suffixes(token.substr(dot + 1));
        for (std::string suffix; std::getline(suffixes, suffix, '/');) channels.push_back(prefix + suffix);
      } else if (token.find(".tif") == std::string::npos) {
        channels.push_back(token);
      }
    }
    rows.emplace_back(name, channels);
    const std::size_t lastBar = line.rfind(" |"), previousBar = line.rfind("| ", lastBar - 1);
    comparisons.push_back(line.substr(previousBar + 2, lastBar - previousBar - 2));
  }
  REQUIRE(rows.size() == layerSpecs().size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const LayerSpec& spec = layerSpecs()[i];
    INFO("docs/outputs.md row " << i << ": " << rows[i].first);
    CHECK(rows[i].first == spec.name);
    std::vector<std::string> expected;
    for (const LayerChannel& c : spec.channels)
      if (c.name) expected.emplace_back(c.name);
    CHECK(rows[i].second == expected);
    CHECK(comparisons[i] == comparisonName(spec.compare));
  }
}

namespace {

// The docs' rows of the analytic shape kinds, written from the registry (host/shapes/registry.h) so
// that a new kind needs no hand edit of docs/: docs/scene-language.md's "analytic shapes" row
// (constructors and their keys) and, in docs/cameras.md's (u, v) table, one row per kind (the
// home's kUv) before the first NURBS row.
std::string analyticShapesRow() {
  std::string constructors, keys;
  shapes::forEachAnalyticKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    constructors += std::string(constructors.empty() ? "" : ", ") + "`Shape." + Kind::kName + "`";
    std::string own;
    for (const char* key : Kind::kKeys) own += std::string(own.empty() ? "" : "; ") + key;
    keys += (keys.empty() ? "`" : ", `") + own + "`";
  });
  return "| analytic shapes | " + constructors + " | " + keys +
         "; all: `location` | [Surface parameters (u, v) per shape](cameras.md#surface-parameters-u-v-per-shape) |";
}

std::string analyticShapesUvRows() {
  std::string rows;
  shapes::forEachAnalyticKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    std::string signature = std::string("Shape.") + Kind::kName + " {";
    for (const char* key : Kind::kKeys) signature += std::string(" ") + key + ";";
    rows += "| `" + signature + " location }` | " + Kind::kUv + " |\n";
  });
  return rows;
}

// Replaces text[begin, end) by `generated`; true when it differed.
bool replaceSpan(std::string& text, std::size_t begin, std::size_t end, const std::string& generated) {
  if (text.compare(begin, end - begin, generated) == 0) return false;
  text.replace(begin, end - begin, generated);
  return true;
}

}  // namespace

TEST_CASE("docs: the shape kinds' rows are the registry's (DICSYNTH_UPDATE_DOCS=1 writes them)") {
  // With DICSYNTH_UPDATE_DOCS=1 the two pages are rewritten instead of compared (after adding a kind:
  // `DICSYNTH_UPDATE_DOCS=1 build/dicsynth_tests -tc="docs: the shape kinds*"`).
  const bool update = std::getenv("DICSYNTH_UPDATE_DOCS") != nullptr;
  const std::string folder = std::string(DS_SOURCE_DIR) + "/docs/";

  std::string language = docText("scene-language.md");
  const std::size_t rowStart = language.find("| analytic shapes |");
  REQUIRE(rowStart != std::string::npos);
  const bool languageChanged = replaceSpan(language, rowStart, language.find('\n', rowStart), analyticShapesRow());

  std::string cameras = docText("cameras.md");
  const std::string header = "| shape | (u, v) |\n|---|---|\n";
  const std::size_t tableStart = cameras.find(header);
  REQUIRE(tableStart != std::string::npos);
  const std::size_t rowsStart = tableStart + header.size();
  const std::size_t nurbsRow = cameras.find("| `Shape.Nurbs {", rowsStart);
  REQUIRE(nurbsRow != std::string::npos);
  const bool camerasChanged = replaceSpan(cameras, rowsStart, nurbsRow, analyticShapesUvRows());

  if (update) {
    if (languageChanged) test::writeBytes(folder + "scene-language.md", language);
    if (camerasChanged) test::writeBytes(folder + "cameras.md", cameras);
    MESSAGE("docs/scene-language.md " << (languageChanged ? "rewritten" : "unchanged") << ", docs/cameras.md "
                                      << (camerasChanged ? "rewritten" : "unchanged"));
  } else {
    INFO("docs/scene-language.md's analytic shapes row or docs/cameras.md's (u, v) rows differ from "
         "host/shapes (run with DICSYNTH_UPDATE_DOCS=1 to write them):\n"
         << analyticShapesRow() << "\n" << analyticShapesUvRows());
    CHECK_FALSE(languageChanged);
    CHECK_FALSE(camerasChanged);
  }
}

TEST_CASE("docs: every reflectance model of the registry is in the scene language's table and the reflectance tables") {
  // host/reflectance/registry.h lists the kinds; docs/scene-language.md's "reflectance" row names
  // each constructor and its keys; docs/reflectance.md has its f_spec row and its parameters.
  const std::string row = tableRow(docText("scene-language.md"), "| reflectance |"), page = docText("reflectance.md");
  reflectance::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    const std::string name = std::string("Shader.") + Kind::kName;
    checkConstructorRow(row, name, Kind::kKeys);
    INFO(name);
    CHECK(page.find("| `" + name + "` | ") != std::string::npos);  // the f_spec table
    // The parameter table: a row naming the kind, `color` and each key in the rows below it.
    const std::size_t parameters = page.find("| constructor | parameter |");
    REQUIRE(parameters != std::string::npos);
    const std::size_t own = page.find("`" + name + "`", parameters);
    REQUIRE(own != std::string::npos);
    const std::size_t next = page.find("\n| `", page.find('\n', own));
    const std::string rows = page.substr(own, next - own);
    CHECK(rows.find("`color`") != std::string::npos);
    for (const char* key : Kind::kKeys) {
      INFO(key);
      CHECK(rows.find(std::string("`") + key + "`") != std::string::npos);
    }
  });
}

TEST_CASE("docs: every Camera.<Kind> of the registry is in the scene language's table with its keys") {
  // host/cameras/registry.h lists the kinds; docs/scene-language.md's "cameras" row names each
  // constructor and its own keys, docs/cameras.md has a section per kind.
  const std::string row = tableRow(docText("scene-language.md"), "| cameras |"), page = docText("cameras.md");
  cameras::forEachCameraKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    const std::string name = std::string("Camera.") + Kind::kName;
    checkConstructorRow(row, name, Kind::kKeys);
    INFO(name);
    CHECK(page.find("`" + name) != std::string::npos);
  });
}

TEST_CASE("docs: every Texture.* kind of the registry is in the scene language's table with its keys") {
  // host/textures/registry.h lists the kinds; docs/scene-language.md's "textures" row names each
  // Texture.* constructor and its keys (the targets' kinds are documented with Target.*).
  const std::string language = docText("scene-language.md"), row = tableRow(language, "| textures |");
  int documented = 0;
  textures::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    if constexpr (textures::isTextureConstructor<Kind>()) {
      ++documented;
      checkConstructorRow(row, Kind::kConstructor, Kind::kKeys);
    } else {
      INFO(Kind::kConstructor);
      CHECK(language.find(std::string("`") + Kind::kConstructor + "`") != std::string::npos);
    }
  });
  CHECK(documented >= 3);  // the scan found them
}

namespace {

// GitHub's anchor of a heading: lower case, punctuation dropped (letters, digits, '-', '_' and
// spaces kept; bytes of other scripts kept as letters), spaces made '-'.
std::string headingAnchor(const std::string& heading) {
  std::string anchor;
  for (unsigned char c : heading) {
    if (c == ' ') anchor += '-';
    else if (std::isalnum(c) || c == '-' || c == '_' || c >= 0x80) anchor += char(std::tolower(c));
  }
  return anchor;
}

// A page without its fenced blocks (a `#` there is a comment, a `](` is code).
std::string withoutFences(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  std::string line;
  bool fenced = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    else if (!fenced) out += line + "\n";
  }
  return out;
}

}  // namespace

TEST_CASE("docs: every relative link of README.md and docs/ names a file that exists, and a heading of it") {
  namespace fs = std::filesystem;
  const fs::path root(DS_SOURCE_DIR);
  std::vector<fs::path> pages = {root / "README.md"};
  for (const auto& e : fs::directory_iterator(root / "docs"))
    if (e.path().extension() == ".md") pages.push_back(e.path());
  const auto anchorsOf = [](const fs::path& page) {
    std::vector<std::string> anchors;
    const std::string text = withoutFences(test::readBytes(page.string()));
    static const std::regex heading(R"((^|\n)#+ +([^\n]*))");
    for (std::sregex_iterator m(text.begin(), text.end(), heading), end; m != end; ++m)
      anchors.push_back(headingAnchor((*m)[2].str()));
    return anchors;
  };
  static const std::regex link(R"(\]\(([^)\s]+)\))");
  int links = 0;
  for (const fs::path& page : pages) {
    const std::string text = withoutFences(test::readBytes(page.string()));
    for (std::sregex_iterator m(text.begin(), text.end(), link), end; m != end; ++m) {
      const std::string target = (*m)[1].str();
      if (std::regex_search(target, std::regex("^[a-z]+:"))) continue;  // https:, mailto:
      ++links;
      INFO(page.filename().string() << ": " << target);
      const std::size_t hash = target.find('#');
      const std::string file = target.substr(0, hash);
      const fs::path resolved = file.empty() ? page : (page.parent_path() / file).lexically_normal();
      REQUIRE(fs::exists(resolved));
      if (hash == std::string::npos || resolved.extension() != ".md") continue;
      const std::vector<std::string> anchors = anchorsOf(resolved);
      CHECK(std::find(anchors.begin(), anchors.end(), target.substr(hash + 1)) != anchors.end());
    }
  }
  CHECK(links > 50);  // the manual's cross references were found (95 on 2026-11-27)
  // The slug rule itself, on headings of this manual.
  CHECK(headingAnchor("Deformed surfaces: `Nurbs.deform`, `Field.load`, `Nurbs.from`") ==
        "deformed-surfaces-nurbsdeform-fieldload-nurbsfrom");
  CHECK(headingAnchor("Surface parameters (u, v) per shape") == "surface-parameters-u-v-per-shape");
}
