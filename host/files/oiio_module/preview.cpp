// Pictures of ground-truth layers (io/preview.h): each layer of an EXR as a PNG in a perceptually
// uniform colour map (OpenImageIO's "viridis"; "turbo" for labels, gray for radiance and masks),
// NaN in a neutral gray, with a colour bar, the layer's name, unit and range written on the
// picture (OpenImageIO's render_text). Part of libdicsynth_oiio.so: OpenImageIO does the reading,
// the colour maps, the text and the PNG writing.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
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
  double scale = 1;  // the file's value times this is shown (an integer image's fractions back to DN)
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

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

// A w × h one-channel float buffer of t in [0, 1] (NaN kept) → RGB of the map (linear light, as
// OpenImageIO's maps are); NaN → gray 0.2 (linear: a mid gray once sRGB-encoded).
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
        const float gray[3] = {0.2140f, 0.2140f, 0.2140f};  // sRGB 128
        rgb.setpixel(x, y, gray);
      }
  return rgb;
}

bool writePng(const OIIO::ImageBuf& linear, const std::string& path, std::string& error) {
  // OpenImageIO's colour maps are linear-light values; a PNG holds sRGB-encoded ones.
  const OIIO::ImageBuf image = OIIO::ImageBufAlgo::colorconvert(linear, "linear", "sRGB");
  if (image.has_error()) {
    error = "cannot convert " + path + " to sRGB: " + image.geterror();
    return false;
  }
  // Complete or absent: written under a temporary name, renamed when done.
  const std::string temp = path + ".tmp.png";
  if (!image.write(temp, OIIO::TypeDesc::UINT8)) {
    error = "cannot write " + path + ": " + image.geterror();
    std::remove(temp.c_str());
    return false;
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    error = "cannot write " + path;
    std::remove(temp.c_str());
    return false;
  }
  return true;
}

bool preview(const PreviewRequest& request, PreviewResult& result, std::string& error) {
  OIIO::ImageBuf exr(request.exrPath);
  if (!exr.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    error = "cannot read " + request.exrPath + ": " + exr.geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = exr.spec();
  std::map<std::string, int> index;
  for (int c = 0; c < spec.nchannels; ++c) index[spec.channelnames[size_t(c)]] = c;

  // The views this file can show: the known layers present, then any other channel as itself.
  std::vector<View> views;
  std::set<std::string> used;
  // An integer image (a sensor TIFF, a PNG): its digital numbers, channel by channel. OpenImageIO
  // hands integers over as fractions of the type's range; they are scaled back to DN (a 10-bit
  // sensor in 16-bit samples shows 0…1023). It was drawn as "radiance 0…1" before (its gray
  // channel is named Y, as the EXR's radiance).
  const OIIO::TypeDesc::BASETYPE base = OIIO::TypeDesc::BASETYPE(exr.nativespec().format.basetype);  // spec(): FLOAT as read
  const bool integer = base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::UINT16 || base == OIIO::TypeDesc::UINT32;
  if (integer) {
    const double top = base == OIIO::TypeDesc::UINT8 ? 255.0 : base == OIIO::TypeDesc::UINT16 ? 65535.0 : 4294967295.0;
    for (int c = 0; c < spec.nchannels; ++c) {
      const std::string& name = spec.channelnames[size_t(c)];
      views.push_back({spec.nchannels == 1 ? "image" : "image." + name, {name}, Map::Gray, "DN", top});
      used.insert(name);
    }
  }
  for (const View& v : integer ? std::vector<View>{} : knownViews()) {  // an integer image holds no EXR layer
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

  // Decimation by an integer: every k-th pixel, so each shown value is one of the file's.
  const int k = std::max(1, (spec.width + request.maxWidth - 1) / std::max(1, request.maxWidth));
  const int w = (spec.width + k - 1) / k, h = (spec.height + k - 1) / k;
  const int title = 30, barArea = 110, barWidth = 16;
  std::error_code ec;
  const std::string font = std::filesystem::exists(request.fontPath, ec) ? request.fontPath : "";
  bool textOk = true;

  for (const View& view : views) {
    // Values and their range over the finite ones.
    OIIO::ImageBuf values(OIIO::ImageSpec(w, h, 1, OIIO::TypeDesc::FLOAT));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double v = 0;
        if (view.channels.size() == 1) {
          v = exr.getchannel(x * k, y * k, 0, index[view.channels[0]]) * view.scale;
        } else {
          for (const std::string& c : view.channels) {
            const double e = exr.getchannel(x * k, y * k, 0, index[c]);
            v += e * e;
          }
          v = std::sqrt(v);
        }
        const float value = float(v);
        values.setpixel(x, y, &value);
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
      }
    if (!(lo <= hi)) {
      result.skipped.push_back(view.name + ": no finite value");
      continue;
    }
    // Radiance and masks from black: below 0 (a texture's interpolation overshoot) shows black.
    if (view.map == Map::Gray && hi > 0) lo = 0;
    const double span = hi > lo ? hi - lo : 1;
    OIIO::ImageBuf t(OIIO::ImageSpec(w, h, 1, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float v = values.getchannel(x, y, 0, 0);
        const float u = std::isfinite(v) ? float(std::clamp((v - lo) / span, 0.0, 1.0)) : std::numeric_limits<float>::quiet_NaN();
        t.setpixel(x, y, &u);
      }
    const OIIO::ImageBuf image = colour(t, view.map);

    // The canvas: white; the title band above, the picture, the colour bar and its labels beside.
    OIIO::ImageBuf canvas(OIIO::ImageSpec(w + barArea, h + title, 3, OIIO::TypeDesc::FLOAT));
    const float white[3] = {1, 1, 1};
    OIIO::ImageBufAlgo::fill(canvas, white);
    OIIO::ImageBufAlgo::paste(canvas, 0, title, 0, 0, image);
    OIIO::ImageBuf ramp(OIIO::ImageSpec(barWidth, h, 1, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < barWidth; ++x) {
        const float u = h > 1 ? 1.0f - float(y) / float(h - 1) : 1.0f;  // the maximum at the top
        ramp.setpixel(x, y, &u);
      }
    OIIO::ImageBufAlgo::paste(canvas, w + 8, title, 0, 0, colour(ramp, view.map));
    const float black[3] = {0, 0, 0};
    const std::string unit = view.unit.empty() ? "" : " (" + view.unit + ")";
    const std::string head = request.stem + ": " + view.name + (view.channels.size() > 1 ? " length" : "") + unit +
                             (k > 1 ? ", pixel step " + std::to_string(k) : "") + "; NaN gray";
    textOk = OIIO::ImageBufAlgo::render_text(canvas, 4, 20, head, 14, font, black) && textOk;
    textOk = OIIO::ImageBufAlgo::render_text(canvas, w + barWidth + 12, title + 12, number(hi), 13, font, black) && textOk;
    textOk = OIIO::ImageBufAlgo::render_text(canvas, w + barWidth + 12, title + h - 2, number(lo), 13, font, black) && textOk;
    if (!view.unit.empty())
      textOk = OIIO::ImageBufAlgo::render_text(canvas, w + barWidth + 12, title + h / 2, view.unit, 13, font, black) && textOk;

    const std::string path = (std::filesystem::path(request.outputDir) / (request.stem + "." + view.name + ".png")).string();
    if (!writePng(canvas, path, error)) return false;
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
