// The C++ registries of kinds (host/shapes, host/reflectance, host/textures, host/cameras:
// registry.h) against the kinds list's rows (shaders/shared/kinds.h), the GLSL registries (the
// X-lists cmake/KindRegistry.cmake generates from those rows under <build>/generated/registry/,
// and shaders/lib/texture.glsl's own) and the twin files they include, read as text: a kind
// registered on one side only, or a twin without its struct and functions, fails here rather than
// as a wrong pixel.
#include <doctest/doctest.h>

#include <cctype>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <variant>

#include "cameras/registry.h"
#include "reflectance/registry.h"
#include "shapes/registry.h"
#include "temp_folder.h"
#include "textures/registry.h"

using namespace dicsynth;

namespace {

std::string readSource(const std::string& relative) { return test::readBytes(std::string(DS_SOURCE_DIR) + "/" + relative); }

// A file cmake/KindRegistry.cmake generated from the kinds list: generated/registry/<name>.
std::string readGenerated(const std::string& name) {
  return test::readBytes(std::string(DS_GENERATED_DIR) + "/registry/" + name);
}

// "BlinnPhong" → "blinn_phong", "GGX" → "ggx": the GLSL twin's name of a kind.
std::string snakeCase(const std::string& name) {
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (i > 0 && std::isupper(c) && std::islower(static_cast<unsigned char>(name[i - 1]))) out += '_';
    out += char(std::tolower(c));
  }
  return out;
}

// The numbers of shaders/shared/kinds.h: DS_SHAPE_SPHERE → 0, ...
std::map<std::string, int> kindNumbers() {
  std::map<std::string, int> numbers;
  const std::string text = readSource("shaders/shared/kinds.h");
  const std::regex define(R"(#define (DS_[A-Z_]+) (\d+))");
  for (std::sregex_iterator it(text.begin(), text.end(), define), end; it != end; ++it)
    numbers[(*it)[1].str()] = std::stoi((*it)[2].str());
  return numbers;
}

// The definition of the X-list macro `list` in `glsl`: it runs to the first line that does not end
// in a backslash.
std::string xListBody(const std::string& glsl, const std::string& list) {
  const std::size_t start = glsl.find("#define " + list + "(X)");
  REQUIRE(start != std::string::npos);
  std::size_t end = start;
  while ((end = glsl.find('\n', end + 1)) != std::string::npos && glsl[end - 1] == '\\') {
  }
  return glsl.substr(start, end - start);
}

// The rows X(DS_KIND, name) of the X-list `list` in `glsl`: kind number → name.
std::map<int, std::string> xListRows(const std::string& glsl, const std::string& list) {
  const std::string body = xListBody(glsl, list);
  const std::map<std::string, int> numbers = kindNumbers();
  std::map<int, std::string> rows;
  const std::regex row(R"(X\((DS_[A-Z_]+), ([a-z_]+)\))");
  for (std::sregex_iterator it(body.begin(), body.end(), row), e; it != e; ++it) {
    INFO((*it)[0].str());
    REQUIRE(numbers.count((*it)[1].str()) == 1);
    const int number = numbers.at((*it)[1].str());
    CHECK(rows.count(number) == 0);  // each kind once
    rows[number] = (*it)[2].str();
  }
  return rows;
}

// The rows X(DS_<KIND>, Type, file) of the family's X-list in kinds.h: kind number → file
// (host/<folder>/<file>.h holds struct <Type>).
std::map<int, std::string> kindsListRows(const std::string& list) {
  const std::string body = xListBody(readSource("shaders/shared/kinds.h"), list);
  const std::map<std::string, int> numbers = kindNumbers();
  std::map<int, std::string> rows;
  const std::regex row(R"(X\((DS_[A-Z_]+), ([A-Za-z]+), ([a-z_]+)\))");
  for (std::sregex_iterator it(body.begin(), body.end(), row), e; it != e; ++it) {
    INFO((*it)[0].str());
    REQUIRE(numbers.count((*it)[1].str()) == 1);
    const int number = numbers.at((*it)[1].str());
    CHECK(rows.count(number) == 0);
    rows[number] = (*it)[3].str();
  }
  return rows;
}

// The twin file shaders/<folder>/<name>.glsl is included by `registry` and defines its struct
// Gpu<Name> (blinn_phong → GpuBlinnPhong, ggx → GpuGgx), ds_<name>_data and each of `functions`
// (ds_<name>_<function>).
void checkTwin(const std::string& registry, const std::string& folder, const std::string& name,
               std::initializer_list<const char*> functions) {
  const std::string path = folder + "/" + name + ".glsl";
  INFO("shaders/" << path);
  CHECK(registry.find("#include \"" + path + "\"") != std::string::npos);
  REQUIRE(std::filesystem::exists(std::string(DS_SOURCE_DIR) + "/shaders/" + path));
  const std::string twin = readSource("shaders/" + path);
  std::string gpuName = "Gpu";
  for (std::size_t i = 0; i < name.size(); ++i)
    if (name[i] != '_')
      gpuName += (i == 0 || name[i - 1] == '_') ? char(std::toupper(static_cast<unsigned char>(name[i]))) : name[i];
  CHECK(twin.find("struct " + gpuName + " {") != std::string::npos);
  CHECK(twin.find(gpuName + " ds_" + name + "_data(") != std::string::npos);
  for (const char* f : functions) CHECK(twin.find(" ds_" + name + "_" + f + "(") != std::string::npos);
}

}  // namespace

TEST_CASE("registries: the GLSL shape registry lists every analytic kind of the C++ one, each with its twin") {
  // The kinds list's rows drive both registries (registry.h static_asserts each row's number
  // against its home); what can still part is a row's file against its home's name, and the
  // includes and list generated from the rows.
  const std::map<int, std::string> kinds = kindsListRows("DS_ANALYTIC_SHAPES");
  const std::string glsl = readGenerated("shape_twins.glsl");
  const std::map<int, std::string> rows = xListRows(glsl, "DS_SHAPE_TWINS");
  CHECK(readSource("shaders/lib/shapes.glsl").find("#include \"registry/shape_twins.glsl\"") != std::string::npos);
  std::set<int> registered;
  shapes::forEachAnalyticKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    INFO("Shape." << Kind::kName);
    const int number = int(Kind::kKind);
    registered.insert(number);
    REQUIRE(kinds.count(number) == 1);
    CHECK(kinds.at(number) == snakeCase(Kind::kName));
    REQUIRE(rows.count(number) == 1);
    CHECK(rows.at(number) == snakeCase(Kind::kName));
    checkTwin(glsl, "shapes", rows.at(number), {"search", "attributes"});
  });
  CHECK(registered.size() == rows.size());  // no GLSL row without a C++ home
  CHECK(registered.size() == kinds.size());
}

TEST_CASE("registries: the GLSL lobe registry lists every reflectance model with a lobe, each with its twin") {
  const std::map<int, std::string> kinds = kindsListRows("DS_REFLECTANCE_MODELS");
  const std::string glsl = readGenerated("reflectance_twins.glsl");
  const std::map<int, std::string> rows = xListRows(glsl, "DS_REFLECTANCE_TWINS");
  CHECK(readSource("shaders/lib/shading.glsl").find("#include \"registry/reflectance_twins.glsl\"") != std::string::npos);
  std::size_t withLobe = 0;
  reflectance::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    INFO("Shader." << Kind::kName);
    const int number = int(Kind::kKind);
    REQUIRE(kinds.count(number) == 1);
    CHECK(kinds.at(number) == snakeCase(Kind::kName));
    if (!Kind::kSpecular) {
      // Constant and Lambert: no lobe, no twin, and the shared code must not need one.
      CHECK(rows.count(number) == 0);
      CHECK(!std::filesystem::exists(std::string(DS_SOURCE_DIR) + "/shaders/reflectance/" + snakeCase(Kind::kName) + ".glsl"));
      return;
    }
    ++withLobe;
    REQUIRE(rows.count(number) == 1);
    CHECK(rows.at(number) == snakeCase(Kind::kName));
    checkTwin(glsl, "reflectance", rows.at(number), {"lobe"});
  });
  CHECK(withLobe == rows.size());
  CHECK(withLobe >= 3);  // the scan found the lobes
  CHECK(kinds.size() == std::variant_size_v<reflectance::Model>);
}

TEST_CASE("registries: the GLSL texture registry draws every texture kind of the C++ one with its twin") {
  // The generated list: X(twin) per twin, and DS_TEXTURE_KINDS_<twin>, the mask of the kinds it
  // draws (the two targets share target.glsl); each twin names its specialization test.
  const std::map<int, std::string> kinds = kindsListRows("DS_TEXTURE_MODELS");
  const std::string glsl = readGenerated("texture_twins.glsl");
  CHECK(readSource("shaders/lib/texture.glsl").find("#include \"registry/texture_twins.glsl\"") != std::string::npos);
  const std::string list = xListBody(glsl, "DS_TEXTURE_TWIN_FILES");
  const std::map<std::string, int> numbers = kindNumbers();
  std::map<int, std::string> twinOfKind;
  std::set<std::string> twins;
  const std::regex row(R"(X\(([a-z_]+)\))"), kindName(R"(DS_TEXTURE_[A-Z_]+)");
  for (std::sregex_iterator it(list.begin(), list.end(), row), e; it != e; ++it) {
    const std::string twin = (*it)[1].str();
    INFO(twin);
    twins.insert(twin);
    const std::string maskName = "#define DS_TEXTURE_KINDS_" + twin + " ";
    const std::size_t at = glsl.find(maskName);
    REQUIRE(at != std::string::npos);
    const std::string drawn = glsl.substr(at + maskName.size(), glsl.find('\n', at) - at - maskName.size());
    for (std::sregex_iterator k(drawn.begin(), drawn.end(), kindName), ke; k != ke; ++k) {
      REQUIRE(numbers.count(k->str()) == 1);
      CHECK(twinOfKind.count(numbers.at(k->str())) == 0);  // each kind drawn by one twin
      twinOfKind[numbers.at(k->str())] = twin;
    }
    CHECK(readSource("shaders/textures/" + twin + ".glsl").find("#define DS_TEXTURE_COMPILED_" + twin + " ") !=
          std::string::npos);
  }
  CHECK(twins.size() >= 3);  // the scan found the rows
  textures::forEachKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    INFO(Kind::kConstructor);
    const int number = int(Kind::kKind);
    REQUIRE(kinds.count(number) == 1);
    if (Kind::kTwin == nullptr) {
      CHECK(kinds.at(number) == snakeCase(Kind::kName));
      CHECK(twinOfKind.count(number) == 0);  // Texture.Constant: GpuObject.shading.y, no twin
      return;
    }
    CHECK(kinds.at(number) == std::string(Kind::kTwin));  // the row names the home and twin file
    REQUIRE(twinOfKind.count(number) == 1);
    CHECK(twinOfKind.at(number) == Kind::kTwin);
    checkTwin(glsl, "textures", Kind::kTwin, {"value"});
  });
  CHECK(kinds.size() == std::variant_size_v<textures::Model>);
}

TEST_CASE("registries: the GLSL camera registry lists every camera kind of the C++ one with a twin") {
  const std::map<int, std::string> kinds = kindsListRows("DS_CAMERA_MODELS");
  const std::string glsl = readGenerated("camera_twins.glsl");
  const std::map<int, std::string> rows = xListRows(glsl, "DS_CAMERA_TWINS");
  CHECK(readSource("shaders/lib/camera.glsl").find("#include \"registry/camera_twins.glsl\"") != std::string::npos);
  std::size_t withTwin = 0;
  cameras::forEachCameraKind([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    INFO("Camera." << Kind::kName);
    const int number = int(Kind::kKind);
    REQUIRE(kinds.count(number) == 1);
    CHECK(kinds.at(number) == snakeCase(Kind::kName));
    if (Kind::kTwin == nullptr) {
      // The pinhole: the default branch of ds_camera_ray, no row and no twin file.
      CHECK(rows.count(number) == 0);
      CHECK(!std::filesystem::exists(std::string(DS_SOURCE_DIR) + "/shaders/cameras/" + snakeCase(Kind::kName) + ".glsl"));
      return;
    }
    ++withTwin;
    REQUIRE(rows.count(number) == 1);
    CHECK(rows.at(number) == std::string(Kind::kTwin));
    CHECK(rows.at(number) == snakeCase(Kind::kName));
    // The twin is included and defines ds_<name>_ray(GpuCamera, ...); its data struct is optional
    // (the orthographic camera's only number is in the intrinsics).
    const std::string path = "cameras/" + rows.at(number) + ".glsl";
    CHECK(glsl.find("#include \"" + path + "\"") != std::string::npos);
    REQUIRE(std::filesystem::exists(std::string(DS_SOURCE_DIR) + "/shaders/" + path));
    CHECK(readSource("shaders/" + path).find("void ds_" + rows.at(number) + "_ray(GpuCamera cam,") != std::string::npos);
  });
  CHECK(withTwin == rows.size());
  CHECK(withTwin >= 2);  // the scan found them
  CHECK(kinds.size() == std::variant_size_v<cameras::Model>);
}

TEST_CASE("registries: the kinds tables are indexed by number and named once") {
  std::set<std::string> names;
  for (const shapes::ShapeKindInfo& k : shapes::kShapeKinds) CHECK(names.insert(std::string("Shape.") + k.name).second);
  for (const reflectance::KindInfo& k : reflectance::kKinds) {
    CHECK(names.insert(std::string("Shader.") + k.name).second);
    CHECK(k.lit == (k.kind != ShaderKind::Constant));
  }
  for (const textures::KindInfo& k : textures::kKinds) CHECK(names.insert(k.constructor).second);
  for (const cameras::CameraKindInfo& k : cameras::kCameraKinds) CHECK(names.insert(std::string("Camera.") + k.name).second);
  CHECK(names.size() == std::size_t(DS_SHAPE_COUNT + DS_SHADER_COUNT + DS_TEXTURE_COUNT + DS_CAMERA_COUNT));
}
