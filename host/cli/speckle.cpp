// dicsynth speckle: writes a speckle texture (black disks on white, or thresholded Perlin noise)
// as a gray TIFF.
//
//   dicsynth speckle -o FILE.tif --size W H [--radius PX | --diameter PX] [--radius-spread F]
//                    [--density F | --count-density N] [--edge-width PX] [--pattern disks|perlin]
//                    [--perlin-cell PX] [--octaves N] [--periodic] [--seed N] [--supersampling S]
//                    [--bits 8|16]
//
//   option             default  meaning
//   -o, --output       -        the TIFF to write (.tif/.tiff); its folder must exist
//   --size W H         -        image size in pixels
//   --radius PX        3        disk radius in pixels (> 0); mean radius with --radius-spread
//   --diameter PX      -        disk diameter in pixels (instead of --radius)
//   --radius-spread F  0        radii uniform in [r(1 − F), r(1 + F)], F in [0, 1)
//   --density F        0.5      expected fraction of the area dark, in (0, 1)
//   --count-density N  -        disks per px² (instead of --density; coverage 1 − exp(−N A_eff))
//   --edge-width PX    0        width of the smooth step across an edge (0: hard edges); disks:
//                               at most the smallest diameter
//   --pattern P        disks    disks (Boolean model) or perlin (thresholded gradient noise)
//   --perlin-cell PX   8        perlin: lattice spacing of the first octave (>= 1)
//   --octaves N        1        perlin: octaves summed, 1..8
//   --periodic         off      the image tiles seamlessly (last column into the first, last row
//                               into the first), for Texture.File { wrap = "repeat" }; perlin: the
//                               size must be a whole number of cells
//   --seed N           1        32-bit seed: the same parameters give the same pixels everywhere
//   --supersampling S  4        S x S samples per pixel (1..8) for anti-aliasing
//   --bits 8|16        16       bits per pixel; value = round(fraction uncovered · (2^bits − 1))
//
// Example (the texture of the paper's Figure 1):
//   dicsynth speckle -o speckle.tif --size 4096 2048 --radius 3 --density 0.5 --seed 1
// Bad parameters exit with code 2 before any file is created. The models: host/texture/speckle.cpp
// (disks, size distribution, soft edges) and host/texture/perlin_speckle.h.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
#include "core/version.h"
#include "files/image_limits.h"
#include "job/render_job.h"
#include "texture/speckle.h"

namespace dicsynth::cli {
namespace {

struct SpeckleOptions {
  std::string output;
  std::vector<int> size;
  SpeckleParams params;
  int bits = 16;
  std::optional<double> diameter;      // given instead of the radius
  std::optional<double> countDensity;  // disks per px², given instead of the density
  bool perlinOptionGiven = false;      // --perlin-cell or --octaves on the command line
  bool diskOptionGiven = false;        // --radius, --diameter, --radius-spread or --count-density
  std::string pattern = "disks";
};

std::string shortest(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

bool hasTiffExtension(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos) return false;
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".tif" || ext == ".tiff";
}

// The options beyond the original ones, when not at their defaults (for the file's description).
std::string extras(const SpeckleOptions& o) {
  const SpeckleParams& p = o.params;
  std::string s;
  if (p.pattern == SpecklePattern::Perlin)
    s += " --pattern perlin --perlin-cell " + shortest(p.perlinCell_px) + " --octaves " + std::to_string(p.perlinOctaves);
  if (p.radiusSpread != 0) s += " --radius-spread " + shortest(p.radiusSpread);
  if (p.disksPerPx2 != 0) s += " --count-density " + shortest(p.disksPerPx2);
  if (p.edgeWidth_px != 0) s += " --edge-width " + shortest(p.edgeWidth_px);
  if (p.periodic) s += " --periodic";
  return s;
}

int runSpeckle(SpeckleOptions options) {
  // Validate everything before any work or file: bad input never leaves a file behind.
  if (options.bits != 8 && options.bits != 16)
    throw InputError("speckle: --bits must be 8 or 16 (got " + std::to_string(options.bits) + ")");
  if (!hasTiffExtension(options.output))
    throw InputError("speckle: " + options.output + ": the output must be a .tif or .tiff file");
  {
    std::error_code ec;
    const std::filesystem::path folder = std::filesystem::path(options.output).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
      throw InputError("speckle: -o " + options.output + ": the folder " + folder.string() + " does not exist");
    checkOutputFile(options.output, "speckle: -o " + options.output, "the image");
  }
  SpeckleParams& p = options.params;
  p.width_px = options.size.at(0);
  p.height_px = options.size.at(1);
  // Given explicitly, 0 is an error like any value out of range (SpeckleParams reads 0 as "not given").
  if (options.diameter) {
    if (!(*options.diameter > 0) || !std::isfinite(*options.diameter))
      throw InputError("speckle: --diameter must be a finite number > 0 px (got " + shortest(*options.diameter) + ")");
    p.radius_px = *options.diameter / 2;
  }
  if (options.countDensity) {
    if (!(*options.countDensity > 0) || !std::isfinite(*options.countDensity))
      throw InputError("speckle: --count-density must be a finite number > 0 disks/px² (got " +
                       shortest(*options.countDensity) + ")");
    p.disksPerPx2 = *options.countDensity;
  }
  if (options.pattern == "perlin")
    p.pattern = SpecklePattern::Perlin;
  else if (options.pattern != "disks")
    throw InputError("speckle: --pattern must be disks or perlin (got " + options.pattern + ")");
  // Ignored by disks, so refused rather than dropped silently (and never checked).
  if (options.perlinOptionGiven && p.pattern != SpecklePattern::Perlin)
    throw InputError("speckle: --perlin-cell and --octaves apply to --pattern perlin (the pattern is disks)");
  if (options.diskOptionGiven && p.pattern == SpecklePattern::Perlin)
    throw InputError("speckle: --radius, --diameter, --radius-spread and --count-density apply to the disks pattern "
                     "(the pattern is perlin)");
  // Peak memory, checked before any buffer exists (as render checks a frame's): per pixel the image
  // (a double), the disks' sample masks (up to 8 bytes, texture/speckle.cpp) and the TIFF's values
  // (2 bytes): 18 bytes. 65536 x 65536 px would need 72 GiB.
  // (A size out of 1..65536 is refused by generateSpeckle, with its own message.)
  if (p.width_px >= 1 && p.height_px >= 1)
    if (const auto shortfall = memoryShortfall(18.0 * double(p.width_px) * double(p.height_px)))
      throw InputError("speckle: a " + std::to_string(p.width_px) + " x " + std::to_string(p.height_px) + " px image " +
                       *shortfall + ": make it smaller");
  const GrayImage image = generateSpeckle(p);  // validates the rest (InputError)

  const double maxValue = double((1u << options.bits) - 1u);
  std::vector<std::uint16_t> values(image.pixels.size());
  double sum = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double scaled = image.pixels[i] * maxValue;  // in [0, maxValue]; halves round up
    values[i] = std::uint16_t(std::floor(scaled + 0.5));
    sum += image.pixels[i];
  }
  // The description is the command that regenerates the file.
  const std::string description =
      std::string("dicsynth ") + kVersion + ": speckle --size " + std::to_string(p.width_px) + " " +
      std::to_string(p.height_px) +
      // The line must run as written: no disk option for perlin, no --density beside --count-density.
      (p.pattern == SpecklePattern::Perlin ? "" : " --radius " + shortest(p.radius_px)) +
      (p.disksPerPx2 != 0 ? "" : " --density " + shortest(p.density)) + " --seed " + std::to_string(p.seed) + " --supersampling " +
      std::to_string(p.supersampling) + " --bits " + std::to_string(options.bits) + extras(options) +
      (p.pattern == SpecklePattern::Perlin ? " (thresholded Perlin noise; value = 1 − mean darkness of the samples)"
                                           : " (black disks on white; value = fraction of the pixel covered by no disk)");
  writeGrayTiff(options.output, p.width_px, p.height_px, values, options.bits, description);

  const double coverage = 1.0 - sum / double(image.pixels.size());
  // Disks as large as the image are few: their coverage is a coin toss, not the density asked for.
  if (p.pattern == SpecklePattern::Disks && p.disksPerPx2 == 0 && std::abs(coverage - p.density) > 0.05)
    std::fprintf(stderr,
                 "dicsynth: warning: speckle: the measured coverage %.4f differs from --density %.4f by more than 0.05: "
                 "with disks of radius %s px on %d x %d px the image holds too few of them (use a smaller radius)\n",
                 coverage, p.density, shortest(p.radius_px).c_str(), p.width_px, p.height_px);
  std::printf("speckle: wrote %s (%d x %d, %d-bit, measured coverage %.4f)\n", options.output.c_str(),
              p.width_px, p.height_px, options.bits, coverage);
  return kExitOk;
}

}  // namespace

void addSpeckleCommand(CLI::App& root, RunFn& run) {
  auto options = std::make_shared<SpeckleOptions>();
  auto* sub = root.add_subcommand("speckle", "Write a speckle texture (black disks on white, or thresholded Perlin noise) as a TIFF");
  sub->add_option("-o,--output", options->output, "TIFF file to write (.tif/.tiff)")->required();
  sub->add_option("--size", options->size, "Image size in pixels: W H")->required()->expected(2);
  auto* radius = sub->add_option("--radius", options->params.radius_px, "Disk radius in pixels")->capture_default_str();
  sub->add_option("--diameter", options->diameter, "Disk diameter in pixels (instead of --radius)")->excludes(radius);
  sub->add_option("--radius-spread", options->params.radiusSpread,
                  "Radii uniform in [r(1-F), r(1+F)], F in [0, 1)")
      ->capture_default_str();
  auto* density = sub->add_option("--density", options->params.density, "Expected dark area fraction, in (0, 1)")
                      ->capture_default_str();
  sub->add_option("--count-density", options->countDensity, "Disks per px² (instead of --density)")
      ->excludes(density);
  sub->add_option("--edge-width", options->params.edgeWidth_px, "Width in px of the smooth step across edges (0: hard)")
      ->capture_default_str();
  sub->add_option("--pattern", options->pattern, "disks (Boolean model) or perlin (thresholded gradient noise)")
      ->capture_default_str();
  sub->add_option("--perlin-cell", options->params.perlinCell_px, "Perlin: lattice spacing in px (>= 1)")
      ->capture_default_str();
  sub->add_option("--octaves", options->params.perlinOctaves, "Perlin: octaves, 1..8")->capture_default_str();
  sub->add_flag("--periodic", options->params.periodic,
                "The image tiles seamlessly (for Texture.File { wrap = \"repeat\" }); perlin: size a whole number of cells");
  sub->add_option("--seed", options->params.seed, "Seed (32-bit unsigned)")->capture_default_str();
  sub->add_option("--supersampling", options->params.supersampling, "Samples per pixel along each axis (1..8)")
      ->capture_default_str();
  sub->add_option("--bits", options->bits, "Bits per pixel: 8 or 16")->capture_default_str();
  sub->callback([&run, options, sub] {
    options->perlinOptionGiven = sub->count("--perlin-cell") + sub->count("--octaves") > 0;
    options->diskOptionGiven =
        sub->count("--radius") + sub->count("--diameter") + sub->count("--radius-spread") + sub->count("--count-density") > 0;
    run = [options] { return runSpeckle(*options); };
  });
}

}  // namespace dicsynth::cli
