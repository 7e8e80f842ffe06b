// The benchmark's JSON rows and its plot: an SVG scatter of time per frame against geometric error,
// both on log scales, written directly (a plot of a dozen points needs no plotting library).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "core/json.h"
#include "job/benchmark.h"

namespace dicsynth {

std::string benchmarkJson(const std::vector<BenchmarkRow>& rows) {
  Json::Value a(Json::arrayValue);
  for (const BenchmarkRow& r : rows) {
    Json::Value o(Json::objectValue);
    o["scene"] = r.scene;
    o["backend"] = r.backend;
    o["precision"] = r.precision;
    o["device"] = r.device;
    o["width"] = r.width;
    o["height"] = r.height;
    o["spp"] = r.samplesPerPixel;
    o["seconds_per_frame"] = json::value(r.secondsPerFrame);
    o["mrays_per_s"] = json::value(r.mraysPerSecond);
    o["geom_err_px_max"] = json::value(r.geomErrPxMax);
    o["geom_err_px_rms"] = json::value(r.geomErrPxRms);
    o["radiance_err_dn_max"] = json::value(r.radianceErrDnMax);
    o["radiance_err_dn_rms"] = json::value(r.radianceErrDnRms);
    o["wrong_hits"] = Json::UInt64(r.wrongHits);
    a.append(o);
  }
  return json::write(a);
}

namespace {

// Decades [lo, hi] covering the positive values (and a floor for zeros).
std::pair<double, double> decades(const std::vector<double>& values, double fallbackLo, double fallbackHi) {
  double lo = INFINITY, hi = 0;
  for (double v : values)
    if (v > 0 && std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (!(hi > 0)) return {fallbackLo, fallbackHi};
  return {std::floor(std::log10(lo)), std::ceil(std::log10(hi)) + (std::log10(hi) == std::ceil(std::log10(hi)))};
}

std::string svgText(double x, double y, const std::string& text, const char* anchor = "middle", int size = 12) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%d\" text-anchor=\"%s\">%s</text>\n", x, y,
                size, anchor, text.c_str());
  return buf;
}

}  // namespace

std::string benchmarkSvg(const std::vector<BenchmarkRow>& rows) {
  const double W = 860, H = 560, left = 90, right = 230, top = 40, bottom = 70;
  const double plotW = W - left - right, plotH = H - top - bottom;
  std::vector<double> times, errors;
  for (const BenchmarkRow& r : rows) {
    times.push_back(r.secondsPerFrame);
    if (r.backend != "cpu") errors.push_back(r.geomErrPxMax);
  }
  const auto [tLo, tHi] = decades(times, -2, 2);
  auto [eLo, eHi] = decades(errors, -15, -3);
  eLo -= 1;  // a decade below the smallest error holds the reference (error 0 by definition)
  auto X = [&](double t) { return left + plotW * (std::log10(t) - tLo) / (tHi - tLo); };
  auto Y = [&](double e) { return top + plotH * (1 - (std::log10(e) - eLo) / (eHi - eLo)); };

  std::ostringstream o;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                W, H);
  o << buf;
  o << svgText(left + plotW / 2, 24, "dicsynth: run time versus geometric error (vs. the CPU reference)", "middle", 15);
  // Axes, decade grid and labels.
  for (int d = int(tLo); d <= int(tHi); ++d) {
    const double x = X(std::pow(10.0, d));
    std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", x, top, x,
                  top + plotH);
    o << buf << svgText(x, top + plotH + 18, "1e" + std::to_string(d));
  }
  for (int d = int(eLo); d <= int(eHi); ++d) {
    const double y = Y(std::pow(10.0, d));
    std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", left, y,
                  left + plotW, y);
    o << buf << svgText(left - 8, y + 4, d == int(eLo) ? "0 (ref.)" : "1e" + std::to_string(d), "end");
  }
  std::snprintf(buf, sizeof buf,
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"black\"/>\n", left,
                top, plotW, plotH);
  o << buf;
  o << svgText(left + plotW / 2, H - 25, "seconds per frame (median)");
  std::snprintf(buf, sizeof buf,
                "<text x=\"22\" y=\"%.1f\" font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 22 %.1f)\">"
                "max geometric error (px)</text>\n",
                top + plotH / 2, top + plotH / 2);
  o << buf;

  // Points: colour by backend × precision, shape by scene.
  const std::map<std::string, std::string> colours = {
      {"cpu fp64", "#000000"}, {"gpu fp32", "#d62728"}, {"gpu df64", "#1f77b4"}, {"gpu fp64", "#2ca02c"}};
  std::map<std::string, int> sceneShape;
  for (const BenchmarkRow& r : rows) sceneShape.emplace(r.scene, int(sceneShape.size()));
  auto marker = [&](double x, double y, int shape, const std::string& colour) {
    char m[256];
    if (shape % 3 == 0)
      std::snprintf(m, sizeof m, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"6\" fill=\"%s\"/>\n", x, y, colour.c_str());
    else if (shape % 3 == 1)
      std::snprintf(m, sizeof m, "<rect x=\"%.1f\" y=\"%.1f\" width=\"11\" height=\"11\" fill=\"%s\"/>\n", x - 5.5,
                    y - 5.5, colour.c_str());
    else
      std::snprintf(m, sizeof m, "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\"/>\n", x, y - 7, x - 6.5,
                    y + 5, x + 6.5, y + 5, colour.c_str());
    return std::string(m);
  };
  for (const BenchmarkRow& r : rows) {
    const std::string key = r.backend + " " + r.precision;
    const auto colour = colours.count(key) ? colours.at(key) : std::string("#888888");
    const double e = r.backend == "cpu" ? std::pow(10.0, eLo) : std::max(r.geomErrPxMax, std::pow(10.0, eLo));
    o << marker(X(r.secondsPerFrame), Y(e), sceneShape[r.scene], colour);
  }
  // Legend.
  double ly = top + 10;
  for (const auto& [key, colour] : colours) {
    o << marker(W - right + 25, ly, 0, colour) << svgText(W - right + 40, ly + 4, key, "start");
    ly += 22;
  }
  ly += 10;
  for (const auto& [scene, shape] : sceneShape) {
    o << marker(W - right + 25, ly, shape, "#555555") << svgText(W - right + 40, ly + 4, scene, "start");
    ly += 22;
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace dicsynth
