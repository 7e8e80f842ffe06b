#include "core/option_names.h"
#include "job/render_args.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/exact_number.h"
#include "core/warning.h"
#include "gpu/device_cache.h"
#include "render/precision_calibration.h"
#include "scene/define_value.h"

namespace dicsynth {

std::vector<std::pair<std::string, std::string>> parseDefines(const std::vector<std::string>& defines) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& d : defines) {
    const auto eq = d.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("-D " + d + ": expected name=value");
    out.emplace_back(d.substr(0, eq), d.substr(eq + 1));
    // "0,002" is the string "0,002" (numbers take a decimal point), which the scene then fails to
    // multiply, at a line of its own: said here, where the cause is.
    const std::string& value = out.back().second;
    const auto comma = value.find(',');
    const auto digits = [](const std::string& s) {
      return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
    };
    if (comma != std::string::npos && digits(value.substr(value[0] == '-' ? 1 : 0, comma - (value[0] == '-' ? 1 : 0))) &&
        digits(value.substr(comma + 1))) {
      warn("-D " + d + ": '" + value + "' is a string, not a number (a decimal comma? write " + value.substr(0, comma) +
           "." + value.substr(comma + 1) + ")");
      continue;
    }
    // Likewise a value that starts as a number and is not one ("0.0O2", "1e-3m"): a typo, nearly
    // always (the docs walk of 2026-11-28 met the scene's "attempt to mul a 'number' with a
    // 'string'" instead). A string meant as such ("2nd") only costs a line.
    const std::size_t sign = value[0] == '-' || value[0] == '+' ? 1 : 0;
    const bool startsNumeric = value.size() > sign && (std::isdigit(static_cast<unsigned char>(value[sign])) ||
                                                       (value[sign] == '.' && value.size() > sign + 1 &&
                                                        std::isdigit(static_cast<unsigned char>(value[sign + 1]))));
    // What Lua reads as a number arrives as one ("3 ", " 0.5": Lua's tonumber allows blanks around
    // it), so no word on it: the warning said "a string" of a value the scene received as 3 (the
    // hostile-input trial of 2026-11-29).
    char* end = nullptr;
    if (startsNumeric && !readDefineNumber(value) && (std::strtod(value.c_str(), &end), *end != '\0'))
      warn("-D " + d + ": '" + value + "' is a string, not a number (from '" + std::string(end) + "' on)");
  }
  return out;
}

std::vector<int> parseFrames(const std::string& text) {
  auto parseInt = [&](const std::string& s) {
    std::size_t used = 0;
    long long v = 0;
    try {
      v = std::stoll(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || s.empty() || v < 0 || !std::isdigit(static_cast<unsigned char>(s[0])))
      throw InputError("--frames " + text + ": expected A:B or N with non-negative integers");
    if (v > kMaxFrameNumber)
      throw InputError("--frames " + text + ": frame numbers go up to " + std::to_string(kMaxFrameNumber));
    return int(v);
  };
  const auto colon = text.find(':');
  if (colon == std::string::npos) return {parseInt(text)};
  const int a = parseInt(text.substr(0, colon)), b = parseInt(text.substr(colon + 1));
  if (b < a) throw InputError("--frames " + text + ": empty range (the range A:B includes both ends)");
  const long long count = static_cast<long long>(b) - a + 1;
  if (count > kMaxFramesPerRun)
    throw InputError("--frames " + text + ": " + std::to_string(count) + " frames, over the limit of " +
                     std::to_string(kMaxFramesPerRun) + " per run: split the range into several runs");
  std::vector<int> frames;
  frames.reserve(std::size_t(count));
  for (long long f = a; f <= b; ++f) frames.push_back(int(f));
  return frames;
}

FrameOrder referenceFirst(std::vector<int> frames, std::optional<int> reference) {
  // Its range as --frames' (it was checked as one of them until it could lie outside: a reference
  // frame -1 was then rendered and recorded, the review of 2026-11-29).
  if (reference && (*reference < 0 || *reference > kMaxFrameNumber))
    throw InputError(optionName("--reference-frame") + " " + std::to_string(*reference) + ": expected a frame number in 0.." +
                     std::to_string(kMaxFrameNumber));
  const int wanted = reference.value_or(frames.front());
  const auto at = std::find(frames.begin(), frames.end(), wanted);
  if (at == frames.end()) {
    frames.insert(frames.begin(), wanted);
    return {std::move(frames), false};
  }
  std::rotate(frames.begin(), at, at + 1);
  return {std::move(frames), true};
}

RenderOptions renderOptions(const RenderArgs& args, int frame) {
  if (args.spp < 1 || args.spp > 65536) throw InputError(optionName("--spp") + " " + std::to_string(args.spp) + ": must be in 1..65536");
  if (args.downscale < 1) throw InputError(optionName("--downscale") + " must be >= 1");
  // Checked with the other options, before work: the precision calibration it steers takes seconds.
  if (!(args.maxErrorPx > 0) || !std::isfinite(args.maxErrorPx))
    throw InputError(optionName("--max-error-px") + " " + shortestNumber(args.maxErrorPx) + ": must be a finite number > 0 (px)");
  RenderOptions o;
  o.samplesPerPixel = args.spp;
  o.seed = args.seed;
  o.frame = frame;
  return o;
}

Precision resolvePrecision(const RenderArgs& args, gpu::Context& context, gpu::Renderer& renderer) {
  if (const auto named = parsePrecision(args.precision)) return *named;
  // Said before measuring: seconds, with the shaders compiled the first time (a fresh machine's first
  // render: 13 s for Figure 1, 27 s for the new-user trial's stereo scene, lavapipe on 2 cores),
  // which passed in silence.
  // Without a cache folder nothing keeps the measurement: every process measures again (the message
  // said "kept in the cache folder" there too: the CI trial of 2026-11-29).
  if (!cachedCalibration(context))
    note("dicsynth: note: precision auto: measuring the error and speed of each precision on " + context.info().name +
         (gpu::deviceCachePath(context, "precision-calibration").empty()
              ? " (no cache folder: DICSYNTH_CACHE_DIR, XDG_CACHE_HOME and HOME are unset, so every run measures "
                "again; name one, or give --precision)"
              : " (once per device and driver; kept in the cache folder)"));
  const PrecisionCalibration calibration = calibratePrecisions(context, renderer);
  const Precision chosen = choosePrecision(calibration, args.maxErrorPx);
  // Said when measured now (the run took seconds for it); from the cache the choice is silent, so
  // that logs of repeated runs stay quiet: the precision is in every output's metadata, the
  // render's lines on stdout and a sweep's manifest, and `dicsynth devices` shows the calibration.
  if (!calibration.fromCache) {
    char maxError[32];
    std::snprintf(maxError, sizeof maxError, "%g", args.maxErrorPx);
    note("dicsynth: note: precision auto: " + std::string(toString(chosen)) + " (the fastest within " + optionName("--max-error-px") + " " + maxError +
         " px; calibration measured on " + context.info().name + ", " + context.info().driver + ": " +
         describeCalibration(calibration) + ")");
  }
  return chosen;
}

std::optional<Precision> knownPrecision(const RenderArgs& args, gpu::Context& context) {
  if (const auto named = parsePrecision(args.precision)) return named;
  const std::optional<PrecisionCalibration> cached = cachedCalibration(context);
  if (!cached) return std::nullopt;
  try {
    return choosePrecision(*cached, args.maxErrorPx);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

void failOnValidationMessages(const gpu::Context& context) {
  const auto messages = context.validationMessages();
  if (messages.empty()) return;
  for (const auto& m : messages) std::fprintf(stderr, "validation: %s\n", m.c_str());
  throw Error("the Vulkan validation layers reported " + std::to_string(messages.size()) + " message(s)");
}

bool stderrIsTerminal() { return isatty(fileno(stderr)) != 0; }

std::function<void(double)> progressPrinter(const std::string& label) {
  if (!stderrIsTerminal()) return nullptr;
  auto last = std::make_shared<int>(-1);
  return [label, last](double fraction) {
    const int percent = int(fraction * 100.0);
    if (percent == *last) return;
    *last = percent;
    std::fprintf(stderr, "\r%s %3d%%%s", label.c_str(), percent, percent >= 100 ? "\n" : "");
    std::fflush(stderr);
  };
}

}  // namespace dicsynth
