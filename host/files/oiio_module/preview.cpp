// Pictures of ground-truth layers (io/preview.h): each layer of an EXR as a PNG in a perceptually
// uniform colour map (OpenImageIO's "viridis"; "turbo" for labels, gray for radiance and masks),
// NaN in a neutral gray, with a colour bar, the layer's name, unit and range written on the
// picture (OpenImageIO's render_text). Part of libdicsynth_oiio.so: OpenImageIO does the reading,
// the colour maps, the text and the PNG encoding; the caller writes the files (request.write).
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "files/oiio_module/oiio_module.h"

namespace {

using dicsynth::PreviewRequest;
using dicsynth::PreviewResult;

enum class Map { Viridis, Gray, Labels };

// One picture: a channel, or the length of a vector of channels.
struct View {
  std::string name;                   // in the PNG's name and title
  std::vector<std::string> channels;  // 1: the value; 2 or 3: the vector's length
  Map map;
  std::string unit;
};

// The dicsynth layers shown (docs/outputs.md: channels and units), in this order.
const std::vector<View>& knownViews() {
  static const std::vector<View> views = {
      {"radiance", {"Y"}, Map::Gray, ""},
      {"depth", {"Z"}, Map::Viridis, "m"},
      {"disp", {"disp.X", "disp.Y", "disp.Z"}, Map::Viridis, "m"},
      {"disp.X", {"disp.X"}, Map::Viridis, "m"},
      {"disp.Y", {"disp.Y"}, Map::Viridis, "m"},
      {"disp.Z", {"disp.Z"}, Map::Viridis, "m"},
      {"flow", {"flow.X", "flow.Y"}, Map::Viridis, "px"},
      {"flow.X", {"flow.X"}, Map::Viridis, "px"},
      {"flow.Y", {"flow.Y"}, Map::Viridis, "px"},
      {"flow.mask", {"flow.mask"}, Map::Gray, ""},
      {"disparity.X", {"disparity.X"}, Map::Viridis, "px"},
      {"disparity.Y", {"disparity.Y"}, Map::Viridis, "px"},
      {"disparity.mask", {"disparity.mask"}, Map::Gray, ""},
      {"objectId", {"objectId"}, Map::Labels, ""},
      {"distortion", {"distortion.X", "distortion.Y"}, Map::Viridis, "px"},
      {"noiseFree", {"noiseFree"}, Map::Viridis, "DN"},
      {"noise", {"noise"}, Map::Viridis, "DN"},
      {"defects", {"defects"}, Map::Labels, ""},
      {"fieldError", {"fieldError.X", "fieldError.Y", "fieldError.Z"}, Map::Viridis, "m"},
  };
  return views;
}

// Channels not drawn, with the reason printed: coordinates of the scene rather than fields to look
// at, and `mask`, which is objectId > 0 (objectId is drawn).
const std::map<std::string, std::string>& notShown() {
  static const std::string coordinate = "a coordinate of the scene, not a field to look at";
  static const std::map<std::string, std::string> reasons = {
      {"P.X", coordinate},  {"P.Y", coordinate},  {"P.Z", coordinate}, {"N.X", coordinate},
      {"N.Y", coordinate},  {"N.Z", coordinate},  {"uv.U", coordinate}, {"uv.V", coordinate},
      {"mask", "objectId > 0, shown by the objectId picture"}};
  return reasons;
}

std::string number(double v, int digits = 4) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

// The range's two labels with as many digits as tell them apart (up to 17, which tells any two
// doubles apart): a field spanning a few float steps around 1 read "1 … 1" with 4 digits (the
// preview audit of 2026-11-28).
std::pair<std::string, std::string> rangeLabels(double lo, double hi) {
  int digits = 4;
  while (lo != hi && digits < 17 && number(lo, digits) == number(hi, digits)) ++digits;
  return {number(lo, digits), number(hi, digits)};
}

// A layer's name as part of a file name: characters other than letters, digits, '.', '-' and '_'
// become '_'. A channel named "a/b" of a foreign EXR had made the name a path into a folder that
// did not exist, and the whole file failed (the preview audit of 2026-11-28).
std::string fileNamePart(const std::string& name) {
  std::string out = name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return out;
}

// sRGB 128 (the gray of values that are not finite) in linear light: ((128/255 + 0.055) / 1.055)^2.4.
constexpr float kNotFiniteGray = 0.21586f;

// A w × h one-channel float buffer of t in [0, 1] (NaN: not finite) → RGB of the map (linear
// light, as OpenImageIO's maps are).
OIIO::ImageBuf colour(const OIIO::ImageBuf& t, Map map) {
  OIIO::ImageBuf rgb;
  if (map == Map::Gray) {
    const float knots[] = {0, 0, 0, 1, 1, 1};  // linear light: sRGB-encoded when written
    rgb = OIIO::ImageBufAlgo::color_map(t, 0, 2, 3, knots);
  } else {
    rgb = OIIO::ImageBufAlgo::color_map(t, 0, map == Map::Viridis ? "viridis" : "turbo");
  }
  const OIIO::ROI roi = t.roi();
  for (int y = roi.ybegin; y < roi.yend; ++y)
    for (int x = roi.xbegin; x < roi.xend; ++x)
      if (std::isnan(t.getchannel(x, y, 0, 0))) {
        const float gray[3] = {kNotFiniteGray, kNotFiniteGray, kNotFiniteGray};
        rgb.setpixel(x, y, gray);
      }
  return rgb;
}

// The picture encoded as PNG in memory; the caller writes the file (request.write). OpenImageIO's
// own file writing reported no error on a full disk: 0-byte PNGs and exit 0 (the preview audit of
// 2026-11-28).
// `description` and `range` become the PNG's text chunks "Description" and "dicsynth:range" (the
// range "LO HI" in 17 digits, for a program or a test to read back: the labels round).
bool encodePng(const OIIO::ImageBuf& linear, const std::string& path, const std::string& description,
               const std::string& range, std::vector<unsigned char>& png, std::string& error) {
  // OpenImageIO's colour maps are linear-light values; a PNG holds sRGB-encoded ones.
  OIIO::ImageBuf image = OIIO::ImageBufAlgo::colorconvert(linear, "linear", "sRGB");
  if (image.has_error()) {
    error = "cannot convert " + path + " to sRGB: " + image.geterror();
    return false;
  }
  image.specmod().attribute("ImageDescription", description);
  image.specmod().attribute("dicsynth:range", range);
  OIIO::Filesystem::IOVecOutput memory(png);
  image.set_write_ioproxy(&memory);
  if (!image.write(path, OIIO::TypeDesc::UINT8, "png")) {
    error = "cannot encode " + path + ": " + image.geterror();
    return false;
  }
  return true;
}

// How a channel's stored numbers read back: OpenImageIO hands an integer channel over as fractions
// of its type's range (a uint32 objectId 1 as 2.3e-10); times `top` and rounded it is the integer
// again (exactly up to 2^23: the float's 24 bits). 0 for a float channel.
double integerTop(OIIO::TypeDesc::BASETYPE base) {
  switch (base) {
    case OIIO::TypeDesc::UINT8: return 255.0;
    case OIIO::TypeDesc::UINT16: return 65535.0;
    case OIIO::TypeDesc::UINT32: return 4294967295.0;
    default: return 0;
  }
}

bool preview(const PreviewRequest& request, PreviewResult& result, std::string& error) {
  OIIO::ImageBuf exr(request.exrPath);
  if (!exr.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    error = "cannot read " + request.exrPath + ": " + exr.geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = exr.spec();
  const OIIO::ImageSpec& native = exr.nativespec();  // spec(): FLOAT as read
  std::map<std::string, int> index;
  std::vector<double> top(std::size_t(spec.nchannels), 0.0);
  for (int c = 0; c < spec.nchannels; ++c) {
    index[spec.channelnames[size_t(c)]] = c;
    const OIIO::TypeDesc type = native.channelformats.empty() ? native.format : native.channelformats[size_t(c)];
    top[size_t(c)] = integerTop(OIIO::TypeDesc::BASETYPE(type.basetype));
  }

  // The views this file can show: the known layers present, then any other channel as itself.
  std::vector<View> views;
  std::set<std::string> used;
  // An integer image that is not an EXR (a sensor TIFF, a PNG): its digital numbers, channel by
  // channel (a 10-bit sensor in 16-bit samples shows 0…1023). It was drawn as "radiance 0…1"
  // before (its gray channel is named Y, as the EXR's radiance). An EXR's integer channels are its
  // layers (objectId, defects), even where it holds no other (the preview audit of 2026-11-28).
  const bool exrFile = std::string(exr.file_format_name()) == "openexr";
  const bool sensorImage = !exrFile && integerTop(OIIO::TypeDesc::BASETYPE(native.format.basetype)) > 0;
  if (sensorImage) {
    for (int c = 0; c < spec.nchannels; ++c) {
      const std::string& name = spec.channelnames[size_t(c)];
      views.push_back({spec.nchannels == 1 ? "image" : "image." + name, {name}, Map::Gray, "DN"});
      used.insert(name);
    }
  }
  for (const View& v : sensorImage ? std::vector<View>{} : knownViews()) {  // a sensor image holds no EXR layer
    bool present = true;
    for (const std::string& c : v.channels) present = present && index.count(c);
    if (!present) continue;
    views.push_back(v);
    for (const std::string& c : v.channels) used.insert(c);
  }
  for (const auto& [name, c] : index) {
    if (used.count(name)) continue;
    if (const auto reason = notShown().find(name); reason != notShown().end()) {
      result.skipped.push_back(name + ": " + reason->second);
      continue;
    }
    views.push_back({name, {name}, Map::Viridis, ""});
  }

  // The number of objects the header names (dicsynth:objects, comma-separated; "" for none).
  std::optional<std::size_t> objectCount;
  if (const OIIO::ParamValue* p = spec.find_attribute("dicsynth:objects", OIIO::TypeDesc::STRING)) {
    const std::string names = p->get_string();
    objectCount = names.empty() ? 0 : std::size_t(std::count(names.begin(), names.end(), ',')) + 1;
  }

  // Decimation by an integer: every k-th pixel, so each shown value is one of the file's.
  const int k = std::max(1, (spec.width + request.maxWidth - 1) / std::max(1, request.maxWidth));
  const int w = (spec.width + k - 1) / k, h = (spec.height + k - 1) / k;
  // The colour bar is at least kMinBar px high, so that its three labels fit beside a picture only
  // a few pixels high (OpenImageIO's render_text aborted the process on labels outside the canvas
  // of a 1- or 2-px-high image: the preview audit of 2026-11-28).
  const int title = 30, barArea = 110, barWidth = 16, kMinBar = 60;
  const int bar = std::max(h, kMinBar);
  std::error_code ec;
  const std::string font = std::filesystem::exists(request.fontPath, ec) ? request.fontPath : "";
  bool textOk = true;
  std::set<std::string> fileNames;
  // The file's pixels as read (FLOAT, channels interleaved, the data window's first pixel first).
  const float* pixels = static_cast<const float*>(exr.localpixels());
  if (pixels == nullptr) {
    error = "cannot read " + request.exrPath + ": no pixels in memory";
    return false;
  }

  for (const View& view : views) {
    // A pixel's value in double: a vector's length beyond float's range stays finite, and lengths
    // a few float steps apart keep their order (they were rounded to float before).
    std::vector<int> channels;
    for (const std::string& c : view.channels) channels.push_back(index[c]);
    const auto valueAt = [&](int x, int y) {
      const float* pixel = pixels + (std::size_t(y) * std::size_t(spec.width) + std::size_t(x)) * std::size_t(spec.nchannels);
      double sum = 0;
      for (int c : channels) {
        double e = pixel[c];
        if (top[size_t(c)] > 0) e = std::round(e * top[size_t(c)]);
        if (channels.size() == 1) return e;
        sum += e * e;
      }
      return std::sqrt(sum);
    };
    // The range over every pixel of the file, not only the shown ones: a wide image's labels gave
    // the shown pixels' range, which could miss its extremes (the preview audit of 2026-11-28).
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int y = 0; y < spec.height; ++y)
      for (int x = 0; x < spec.width; ++x)
        if (const double v = valueAt(x, y); std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(lo <= hi)) {
      result.skipped.push_back(view.name + ": no finite value");
      continue;
    }
    // Radiance and masks from black: below 0 (a texture's interpolation overshoot) shows black.
    if (view.map == Map::Gray && hi > 0) lo = 0;
    // objectId over the scene's objects, 0 to their count in the header, not over the ids present:
    // an object leaving the view recoloured every other one between two frames of a sequence (the
    // preview audit of 2026-11-28). A file's ids beyond the count (not dicsynth's) widen it.
    if (view.name == "objectId" && objectCount) lo = 0, hi = std::max(hi, double(*objectCount));
    const double span = hi - lo;
    OIIO::ImageBuf t(OIIO::ImageSpec(w, h, 1, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double v = valueAt(x * k, y * k);
        // A constant field shows the map's bottom colour (and says so in its title).
        const float u = !std::isfinite(v) ? std::numeric_limits<float>::quiet_NaN()
                                          : span > 0 ? float(std::clamp((v - lo) / span, 0.0, 1.0)) : 0.0f;
        t.setpixel(x, y, &u);
      }
    const OIIO::ImageBuf image = colour(t, view.map);

    // The canvas: white; the title band above, the picture, the colour bar and its labels beside.
    OIIO::ImageBuf canvas(OIIO::ImageSpec(w + barArea, bar + title, 3, OIIO::TypeDesc::FLOAT));
    const float white[3] = {1, 1, 1};
    OIIO::ImageBufAlgo::fill(canvas, white);
    OIIO::ImageBufAlgo::paste(canvas, 0, title, 0, 0, image);
    OIIO::ImageBuf ramp(OIIO::ImageSpec(barWidth, bar, 1, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < bar; ++y)
      for (int x = 0; x < barWidth; ++x) {
        const float u = span > 0 ? 1.0f - float(y) / float(bar - 1) : 0.0f;  // the maximum at the top
        ramp.setpixel(x, y, &u);
      }
    OIIO::ImageBufAlgo::paste(canvas, w + 8, title, 0, 0, colour(ramp, view.map));
    const float black[3] = {0, 0, 0};
    const std::string unit = view.unit.empty() ? "" : " (" + view.unit + ")";
    const std::string head = request.stem + ": " + view.name + (view.channels.size() > 1 ? " length" : "") + unit +
                             (span > 0 ? "" : ", constant") + (k > 1 ? ", pixel step " + std::to_string(k) : "") +
                             "; NaN/inf gray";
    const auto [loText, hiText] = rangeLabels(lo, hi);
    textOk = OIIO::ImageBufAlgo::render_text(canvas, 4, 20, head, 14, font, black) && textOk;
    textOk = OIIO::ImageBufAlgo::render_text(canvas, w + barWidth + 12, title + 12, hiText, 13, font, black) && textOk;
    textOk = OIIO::ImageBufAlgo::render_text(canvas, w + barWidth + 12, title + bar - 2, loText, 13, font, black) && textOk;
    if (!view.unit.empty())
      textOk = OIIO::ImageBufAlgo::render_text(canvas, w + barWidth + 12, title + bar / 2, view.unit, 13, font, black) && textOk;

    // Two channels whose names differ only in characters a file name cannot hold get one name each.
    std::string name = request.stem + "." + fileNamePart(view.name);
    for (int n = 2; fileNames.count(name); ++n) name = request.stem + "." + fileNamePart(view.name) + "_" + std::to_string(n);
    fileNames.insert(name);
    const std::string path = (std::filesystem::path(request.outputDir) / (name + ".png")).string();
    std::vector<unsigned char> png;
    const std::string range = number(lo, 17) + " " + number(hi, 17);
    if (!encodePng(canvas, path, head + "; range " + range + unit, range, png, error)) return false;
    if (!request.write(path, png)) return false;  // the caller keeps why
    result.written.push_back(path);
  }
  if (!textOk) result.skipped.push_back("labels: OpenImageIO could not render text (no font found)");
  return true;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) bool dicsynth_oiio_preview(const PreviewRequest* request,
                                                                             PreviewResult* result, std::string* error) {
  try {
    return preview(*request, *result, *error);
  } catch (const std::exception& e) {
    *error = std::string("preview failed: ") + e.what();
    return false;
  }
}

static_assert(std::is_same_v<decltype(&dicsynth_oiio_preview), dicsynth::PreviewFn>);
