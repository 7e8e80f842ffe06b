// Fuzzing the inputs a user hands dicsynth: mutated example scenes and damaged texture files, run
// through the CLI as a user would (README, "Limits"). With a fixed seed, so a failure reproduces:
// the message names the mutant, which stays on disk when DICSYNTH_FUZZ_KEEP=1.
//   CI size: 120 scene mutants and every texture mutant below, well under a minute on 2 cores.
//   Long run: DICSYNTH_FUZZ_MUTANTS=5000 (scenes) and DICSYNTH_FUZZ_TEXTURES=2000.
// What must hold for every run: exit 0, 2 or 3 as documented, never a signal; bounded time and
// memory; after exit 2 no output folder; a scene error that names the scene file names its line
// (except the file-level errors listed below); after exit 0 a finite radiance everywhere.
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "exr_test_util.h"
#include "run_cli.h"

using namespace dicsynth;

namespace {

std::size_t countFromEnv(const char* name, std::size_t fallback) {
  const char* text = std::getenv(name);
  return text ? std::size_t(std::strtoull(text, nullptr, 10)) : fallback;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string joined(const std::vector<std::string>& ls) {
  std::string out;
  for (const std::string& l : ls) out += l + "\n";
  return out;
}

// One mutation of a scene's text, chosen by `rng`; `what` says which, for the failure message.
std::string mutate(const std::string& text, std::mt19937& rng, std::string& what) {
  std::vector<std::string> ls = lines(text);
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const std::vector<std::string> numbers = {"1e308", "-1e308", "1e-308", "0", "-1", "-0.5", "(0/0)", "(1/0)", "(-1/0)",
                                            "'text'", "{}", "true", "nil", "2^53", "65536", "1e9", "-1e9", "4294967296"};
  switch (pick(8)) {
    case 0: {  // delete a line
      const std::size_t i = pick(ls.size());
      what = "delete line " + std::to_string(i + 1);
      ls.erase(ls.begin() + std::ptrdiff_t(i));
      break;
    }
    case 1: {  // duplicate a line
      const std::size_t i = pick(ls.size());
      what = "duplicate line " + std::to_string(i + 1);
      ls.insert(ls.begin() + std::ptrdiff_t(i), ls[i]);
      break;
    }
    case 2: {  // swap two lines
      const std::size_t i = pick(ls.size()), j = pick(ls.size());
      what = "swap lines " + std::to_string(i + 1) + " and " + std::to_string(j + 1);
      std::swap(ls[i], ls[j]);
      break;
    }
    case 3:
    case 4:
    case 5: {  // a number (or a number-like token) becomes something else
      static const std::regex number(R"((^|[^A-Za-z0-9_.])(-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?))");
      std::vector<std::pair<std::size_t, std::size_t>> spots;  // (line, offset of the number)
      for (std::size_t i = 0; i < ls.size(); ++i)
        for (auto it = std::sregex_iterator(ls[i].begin(), ls[i].end(), number); it != std::sregex_iterator(); ++it)
          spots.emplace_back(i, std::size_t(it->position(2)));
      if (spots.empty()) return mutate(text, rng, what);
      const auto [i, at] = spots[pick(spots.size())];
      std::smatch m;
      const std::string rest = ls[i].substr(at);
      std::regex_search(rest, m, std::regex(R"(^-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?)"));
      const std::string replacement = numbers[pick(numbers.size())];
      what = "line " + std::to_string(i + 1) + ": " + m.str() + " -> " + replacement;
      ls[i] = ls[i].substr(0, at) + replacement + rest.substr(std::size_t(m.length()));
      break;
    }
    case 6: {  // truncate at a random byte
      const std::size_t n = pick(text.size());
      what = "truncate at byte " + std::to_string(n);
      return text.substr(0, n);
    }
    default: {  // random bytes inserted
      std::string t = text;
      const std::size_t at = pick(t.size()), n = 1 + pick(8);
      std::string bytes;
      for (std::size_t k = 0; k < n; ++k) bytes += char(pick(256));
      what = "insert " + std::to_string(n) + " random bytes at " + std::to_string(at);
      return t.insert(at, bytes);
    }
  }
  return joined(ls);
}

struct Run {
  int exitCode = -1;  // -1: not a normal exit (a signal)
  int signal = 0;
  double seconds = 0;
  long maxRssKb = 0;
  std::string err;
};

// Runs the CLI with `arguments` in a child with a time limit (SIGKILL after `limit` s), recording
// its exit, its peak memory (getrusage of the child) and stderr.
Run runBounded(const std::string& arguments, double limit, const test::TempFolder& dir) {
  const std::string errFile = dir.file("stderr.txt");
  const std::string command = "exec timeout -s KILL " + std::to_string(int(limit)) + " " + std::string(DS_BINARY) + " " +
                              arguments + " >/dev/null 2>" + errFile;
  const auto start = std::chrono::steady_clock::now();
  struct rusage before {};
  getrusage(RUSAGE_CHILDREN, &before);
  const int status = std::system(command.c_str());
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  struct rusage after {};
  getrusage(RUSAGE_CHILDREN, &after);
  r.maxRssKb = after.ru_maxrss;  // the largest of any child so far: an upper bound for this one
  if (WIFEXITED(status)) {
    r.exitCode = WEXITSTATUS(status);
    if (r.exitCode == 124 || r.exitCode == 137) r.exitCode = -1, r.signal = SIGKILL;  // timeout
  } else if (WIFSIGNALED(status)) {
    r.signal = WTERMSIG(status);
  }
  r.err = test::readBytes(errFile);
  return r;
}

// Scene errors that concern the whole file and so carry no line.
bool fileLevelError(const std::string& message) {
  for (const char* known : {"the scene defines no camera", "cannot read the scene file", "a frame of",
                            "the scene's NURBS surfaces need", "the scene's textures hold", "--layers",
                            "beyond float32"})
    if (message.find(known) != std::string::npos) return true;
  return false;
}

// The checks every run must pass (header comment). `scene`: the scene path as given.
void checkRun(const Run& r, const std::string& scene, const std::string& out, const std::string& what) {
  INFO(what << "\nexit " << r.exitCode << ", signal " << r.signal << ", " << r.seconds << " s\nstderr: " << r.err);
  CHECK(r.signal == 0);
  CHECK((r.exitCode == 0 || r.exitCode == 2 || r.exitCode == 3));
  if (r.exitCode == 2) CHECK(!std::filesystem::exists(out));
  for (const std::string& line : lines(r.err)) {
    if (line.rfind(scene + ":", 0) != 0) continue;
    const std::string after = line.substr(scene.size() + 1);
    const bool withLine = !after.empty() && std::isdigit(static_cast<unsigned char>(after[0]));
    CHECK_MESSAGE((withLine || fileLevelError(after)), "an error about the scene without its line: " << line);
  }
  if (r.exitCode != 0) return;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    if (entry.path().extension() != ".exr") continue;
    const test::ExrContents exr = test::readExr(entry.path().string());
    if (!exr.floats.count("Y")) continue;
    const std::vector<float>& y = exr.floats.at("Y");
    // Finite everywhere (background included); not necessarily >= 0: the interpolating B-spline of
    // a texture overshoots near sharp texel edges (README, the Y channel).
    CHECK_MESSAGE(std::all_of(y.begin(), y.end(), [](float v) { return std::isfinite(v); }),
                  entry.path().string() << ": radiance not finite");
  }
}

}  // namespace

TEST_CASE("fuzz: mutated example scenes exit 0, 2 or 3, never crash or hang, and say where") {
  test::TempFolder dir;
  const std::filesystem::path scenes = std::filesystem::path(DS_SOURCE_DIR) / "scenes";
  // The scenes' relative files, beside the mutants.
  std::filesystem::create_directory_symlink(scenes / "data", dir.path() / "data");
  std::filesystem::create_symlink(scenes / "speckle.tif", dir.path() / "speckle.tif");
  std::vector<std::pair<std::string, std::string>> originals;
  for (const auto& entry : std::filesystem::directory_iterator(scenes))
    if (entry.path().extension() == ".lua") originals.emplace_back(entry.path().filename().string(), test::readBytes(entry.path().string()));
  std::sort(originals.begin(), originals.end());
  const std::size_t mutants = countFromEnv("DICSYNTH_FUZZ_MUTANTS", 120);
  const bool keep = std::getenv("DICSYNTH_FUZZ_KEEP") != nullptr;
  std::mt19937 rng(std::uint32_t(countFromEnv("DICSYNTH_FUZZ_SEED", 20261125)));  // another seed: other mutants
  std::size_t exits[4] = {0, 0, 0, 0};
  double slowest = 0;
  long largestKb = 0;
  for (std::size_t k = 0; k < mutants; ++k) {
    const auto& [name, text] = originals[k % originals.size()];
    std::string what;
    const std::string mutant = mutate(text, rng, what);
    const std::string path = dir.write("m" + std::to_string(k) + "_" + name, mutant);
    const std::string out = dir.file("out" + std::to_string(k));
    // Small and quick: 1/16 of the resolution, one sample, the CPU reference, no EXR conversions
    // beyond the radiance; the time limit well above any example's (0.2 s here).
    const Run r = runBounded("render " + path + " -o " + out + " --backend cpu --downscale 16 --spp 1 --layers image,radiance",
                             60, dir);
    checkRun(r, path, out, "mutant " + std::to_string(k) + " of " + name + ": " + what);
    CHECK(r.seconds < 60);
    if (r.exitCode >= 0 && r.exitCode <= 3) ++exits[r.exitCode];
    slowest = std::max(slowest, r.seconds);
    largestKb = std::max(largestKb, r.maxRssKb);
    std::error_code ec;
    std::filesystem::remove_all(out, ec);
    if (!keep) std::filesystem::remove(path, ec);
  }
  MESSAGE(mutants << " scene mutants: exit 0: " << exits[0] << ", exit 2: " << exits[2] << ", exit 3: " << exits[3]
                  << "; slowest " << slowest << " s, largest " << largestKb / 1024 << " MiB");
  CHECK(largestKb < 4L << 20);  // 4 GiB: far above an example's ~0.5 GiB, far below the machine
  CHECK(exits[2] > mutants / 10);  // the mutations do reach the checks (not all absorbed)
}

TEST_CASE("fuzz: damaged texture files of every format read here are exit 0 or 2, never a crash") {
  test::TempFolder dir;
  // Valid originals: a 48 × 40 gradient in the formats and sample types OpenImageIO writes here.
  struct Format {
    std::string extension;
    OIIO::TypeDesc type;
    int channels;
  };
  const std::vector<Format> formats = {{".tif", OIIO::TypeDesc::UINT8, 1},  {".tif", OIIO::TypeDesc::UINT16, 3},
                                       {".tif", OIIO::TypeDesc::FLOAT, 1},  {".png", OIIO::TypeDesc::UINT8, 1},
                                       {".png", OIIO::TypeDesc::UINT16, 3}, {".exr", OIIO::TypeDesc::HALF, 1},
                                       {".exr", OIIO::TypeDesc::FLOAT, 3},  {".jpg", OIIO::TypeDesc::UINT8, 3},
                                       {".bmp", OIIO::TypeDesc::UINT8, 3},  {".pgm", OIIO::TypeDesc::UINT8, 1},
                                       {".hdr", OIIO::TypeDesc::FLOAT, 3},  {".tga", OIIO::TypeDesc::UINT8, 1}};
  std::vector<std::string> originals;
  for (std::size_t f = 0; f < formats.size(); ++f) {
    const Format& format = formats[f];
    const int w = 48, h = 40;
    std::vector<float> pixels(std::size_t(w * h * format.channels));
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = float(i % 97) / 97.0f;
    const std::string path = dir.file("original" + std::to_string(f) + format.extension);
    auto out = OIIO::ImageOutput::create(path);
    REQUIRE_MESSAGE(out, path);
    REQUIRE(out->open(path, OIIO::ImageSpec(w, h, format.channels, format.type)));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(out->close());
    originals.push_back(path);
  }
  const std::size_t mutants = countFromEnv("DICSYNTH_FUZZ_TEXTURES", 96);
  std::mt19937 rng(std::uint32_t(countFromEnv("DICSYNTH_FUZZ_SEED", 77)));
  std::size_t exits[4] = {0, 0, 0, 0};
  for (std::size_t k = 0; k < mutants; ++k) {
    const std::string& original = originals[k % originals.size()];
    std::string bytes = test::readBytes(original);
    auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
    std::string what;
    switch (pick(3)) {
      case 0:
        what = "truncated at " + std::to_string(bytes.size() / 2);
        bytes.resize(pick(bytes.size()));
        break;
      case 1: {
        const std::size_t flips = 1 + pick(16);
        what = std::to_string(flips) + " bit flips";
        for (std::size_t i = 0; i < flips; ++i) bytes[pick(bytes.size())] ^= char(1 << pick(8));
        break;
      }
      default: {  // the header's first 64 bytes overwritten with random ones (sizes, offsets, tags)
        what = "random header bytes";
        for (std::size_t i = 0; i < 8 && i < bytes.size(); ++i) bytes[pick(std::min<std::size_t>(64, bytes.size()))] = char(pick(256));
        break;
      }
    }
    const std::string texture = dir.file("t" + std::to_string(k) + std::filesystem::path(original).extension().string());
    std::ofstream(texture, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    const std::string scene = dir.write(
        "s" + std::to_string(k) + ".lua",
        "cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.012; pixelSize = {2e-4, 2e-4} }\n"
        "plate = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 1} };\n"
        "  texture = Texture.File { fileName = '" + texture + "' } }\n");
    const std::string out = dir.file("out" + std::to_string(k));
    const Run r = runBounded("render " + scene + " -o " + out + " --backend cpu --spp 1 --layers image,radiance", 60, dir);
    checkRun(r, scene, out, "texture mutant " + std::to_string(k) + " of " + original + ": " + what);
    CHECK(r.exitCode != 3);  // a damaged input is the user's error (2), not an internal one
    if (r.exitCode >= 0 && r.exitCode <= 3) ++exits[r.exitCode];
    std::error_code ec;
    std::filesystem::remove_all(out, ec);
  }
  MESSAGE(mutants << " texture mutants: exit 0: " << exits[0] << ", exit 2: " << exits[2]);
}
