// The sensor and its post-processors in a scene: Sensor.Emva, Blur.Gaussian, Blur.Disk,
// Vignetting.Cos4, Vignetting.Radial, Dust, DefectivePixels, and the camera keys `sensor` and
// `postProcessing` that take them (readCameraSensor). What they do: host/sensor, docs/sensor.md.
//
// Example:
//   camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.016; pixelSize = {5e-6, 5e-6};
//     bitsPerPixel = 12; exposure = 0.8;
//     sensor = Sensor.Emva { preset = "machine-vision-cmos"; readNoise_e = 3 };
//     postProcessing = { Blur.Gaussian { sigma_px = 0.8 }, Vignetting.Cos4 {},
//                        Dust { center_px = {200, 150}; radius_px = 40; opacity = 0.3 },
//                        DefectivePixels { dead = 1e-4; hot = 1e-4; stuck = {{10, 20}} } } }
// The order inside postProcessing does not matter: the pipeline's order is fixed (docs/sensor.md).
#include "scene/sensor_constructors.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "sensor/sensor_presets.h"

namespace dicsynth::scene {

// One element of a camera's postProcessing list.
struct PostProcessorValue {
  enum class Kind { Blur, Vignetting, Dust, Defects } kind = Kind::Blur;
  std::string constructor;  // "Blur.Gaussian", ... for messages
  int line = 0;             // the scene line of its constructor: what the camera's checks name
  Blur blur;
  Vignetting vignetting;
  DustBlob dust;
  DefectivePixels defects;
};

template <>
inline constexpr const char* kUserdataName<EmvaSensor> = "Sensor";
template <>
inline constexpr const char* kUserdataName<PostProcessorValue> = "PostProcessor";

namespace {

void pushPostProcessor(lua_State* L, PostProcessorValue value) {
  value.line = LuaSandbox::currentLine(L);
  pushUserdata(L, std::move(value));
}

/* ------------------------------------------------------------------------------------------------
Sensor.Emva: the linear camera model of EMVA 1288 (docs/sensor.md has the formulas). Every value
not given comes from the preset, else from the defaults below (the "machine-vision-cmos" preset's
values, then the derived ones).

  Parameter           | Unit       | Default                       | Meaning
  --------------------+------------+-------------------------------+-------------------------------
  preset              | string     | none                          | a name of sensor_presets.h
  quantumEfficiency   | e⁻/photon  | preset (0.65)                 | η, in (0, 1]
  fullWell_e          | e⁻         | preset (10500)                | saturation capacity, in
                      |            |                               | [1, 1e9] (kMaxFullWell_e)
  readNoise_e         | e⁻ rms     | preset (2.4)                  | temporal dark noise σ_d, in
                      |            |                               | [0, 1e9]
  darkCurrent_e_per_s | e⁻/s       | preset (3)                    | >= 0
  exposureTime_s      | s          | preset (0.01)                 | integration of dark current
  photonsAtFullScale  | photons    | fullWell_e / η                | photons per pixel at
                      |            |                               | exposure·radiance = 1, <= 1e15
  gain_DN_per_e       | DN/e⁻      | (2^b - 1 - offset)/fullWell_e | K, overall system gain, in
                      |            |                               | (0, 65535]
  darkOffset_DN       | DN         | floor((2^b - 1)/64)           | black level, >= 0, < 2^b - 1
  shotNoise           | boolean    | true                          | false: no Poisson noise
  prnu                | fraction   | 0                             | photo-response nonuniformity,
                      |            |                               | rms relative gain, in [0, 0.25]
  dsnu_e              | e⁻ rms     | 0                             | dark-signal nonuniformity, in
                      |            |                               | [0, 1e9]
------------------------------------------------------------------------------------------------ */
// The largest full well: the Poisson sampler's acceptance test (sensor/noise_sampling.cpp, PTRS)
// compares log-probabilities of size ~μ ln μ, which double carries to ~μ ln μ · 2^-53: 2e-6 at
// μ = 1e9 (a relative error of 2e-6 in an acceptance probability), 3e-3 at 1e12, and at 1e15 and
// beyond the variance was measured wrong by −16 % to +65 % (the sensor trial of 2026-11-29; at 1e30
// every pixel read the dark offset). The mean drawn is at most fullWell_e + 40 √fullWell_e + 1000
// (sensor.cpp skips the draw beyond: saturation is certain), so bounding the well bounds every
// draw. Real sensors hold 1e3 to ~2e6 e⁻. The read noise shares the bound (it is a count of
// electrons too, and keeps K σ_d z finite); the gain is at most 65535 DN per electron (one electron
// would span more than the whole 16-bit range); 1e15 photons at full scale keep η μ_p finite.
constexpr double kMaxFullWell_e = 1e9;
constexpr double kMaxGain_DN_per_e = 65535;
constexpr double kMaxPhotonsAtFullScale = 1e15;

int sensorEmva(lua_State* L) {
  Params p(L, "Sensor.Emva",
           {"preset", "quantumEfficiency", "fullWell_e", "readNoise_e", "darkCurrent_e_per_s", "exposureTime_s",
            "photonsAtFullScale", "gain_DN_per_e", "darkOffset_DN", "shotNoise", "prnu", "dsnu_e"});
  EmvaSensor s;
  if (auto preset = p.string("preset")) {
    if (!findSensorPreset(*preset))
      p.fail("unknown 'preset' \"" + *preset + "\"; the presets are " + sensorPresetNames());
    s.preset = *preset;
  }
  // Each value, when given, must satisfy `ok`; `condition` says which values do.
  auto checked = [&](const char* key, std::optional<double>& into, auto ok, const char* condition) {
    into = p.number(key);
    if (into) p.require(ok(*into), key, condition, *into);
  };
  const auto nonNegative = [](double v) { return v >= 0; };
  checked("quantumEfficiency", s.quantumEfficiency, [](double v) { return v > 0 && v <= 1; }, "in (0, 1]");
  checked("fullWell_e", s.fullWell_e, [](double v) { return v >= 1 && v <= kMaxFullWell_e; },
          "in [1, 1e9] e⁻ (a well of less than one electron holds none; beyond 1e9 the shot-noise sampler loses "
          "accuracy, and real sensors hold up to ~2e6)");
  checked("readNoise_e", s.readNoise_e, [](double v) { return v >= 0 && v <= kMaxFullWell_e; }, "in [0, 1e9] e⁻ rms");
  checked("darkCurrent_e_per_s", s.darkCurrent_e_per_s, nonNegative, ">= 0");
  checked("exposureTime_s", s.exposureTime_s, nonNegative, ">= 0");
  checked("photonsAtFullScale", s.photonsAtFullScale, [](double v) { return v > 0 && v <= kMaxPhotonsAtFullScale; },
          "in (0, 1e15] photons");
  checked("gain_DN_per_e", s.gain_DN_per_e, [](double v) { return v > 0 && v <= kMaxGain_DN_per_e; },
          "in (0, 65535] DN/e⁻ (more would put one electron beyond the whole 16-bit range)");
  checked("darkOffset_DN", s.darkOffset_DN, nonNegative, ">= 0");
  s.shotNoise = p.boolean("shotNoise").value_or(true);
  // The relative response 1 + prnu z is clipped at 0 for a fraction Φ(−1/prnu) of the pixels: 3e-5
  // at 0.25, 2.3 % at 0.5, no longer the normal spread it stands for. Sensors show 0.5–3 %.
  s.prnu = p.number("prnu", 0.0);
  p.require(s.prnu >= 0 && s.prnu <= 0.25, "prnu", "in [0, 0.25] (a fraction: 0.01 is 1 % rms)", s.prnu);
  s.dsnu_e = p.number("dsnu_e", 0.0);
  p.require(s.dsnu_e >= 0 && s.dsnu_e <= kMaxFullWell_e, "dsnu_e", "in [0, 1e9] e⁻ rms", s.dsnu_e);
  // The default photonsAtFullScale, fullWell_e / η, within its bound too (a tiny η).
  if (!s.photonsAtFullScale) {
    const double derived = photonsAtFullScale(s);
    if (!(derived <= kMaxPhotonsAtFullScale))
      p.fail("photonsAtFullScale = fullWell_e / quantumEfficiency = " + formatNumber(derived) +
             " photons is over 1e15: give a larger quantumEfficiency or photonsAtFullScale itself");
  }
  pushUserdata(L, std::move(s));
  return 1;
}

/* Blur.Gaussian { sigma_px }: Gaussian PSF, sigma_px > 0 (px, required).
   Blur.Disk { radius_px }: defocus disk (uniform circle of confusion), radius_px > 0 (px, required). */
int blurGaussian(lua_State* L) {
  Params p(L, "Blur.Gaussian", {"sigma_px"});
  PostProcessorValue v{PostProcessorValue::Kind::Blur, p.constructor()};
  v.blur.kind = BlurKind::Gaussian;
  v.blur.sigma_px = p.requiredNumber("sigma_px");
  p.require(v.blur.sigma_px > 0 && v.blur.sigma_px <= 100, "sigma_px", "in (0, 100] (px)", v.blur.sigma_px);
  pushPostProcessor(L, std::move(v));
  return 1;
}

int blurDisk(lua_State* L) {
  Params p(L, "Blur.Disk", {"radius_px"});
  PostProcessorValue v{PostProcessorValue::Kind::Blur, p.constructor()};
  v.blur.kind = BlurKind::Disk;
  v.blur.radius_px = p.requiredNumber("radius_px");
  p.require(v.blur.radius_px > 0 && v.blur.radius_px <= 100, "radius_px", "in (0, 100] (px)", v.blur.radius_px);
  pushPostProcessor(L, std::move(v));
  return 1;
}

/* Vignetting.Cos4 {}: the natural cos⁴ fall-off of the camera's lens (no parameters).
   Vignetting.Radial { coefficients = {a1[, a2[, a3]]} }: factor 1 + a1 ρ² + a2 ρ⁴ + a3 ρ⁶ (ρ = 1
   at the half-diagonal), clipped at 0. */
int vignettingCos4(lua_State* L) {
  Params p(L, "Vignetting.Cos4", {});
  PostProcessorValue v{PostProcessorValue::Kind::Vignetting, p.constructor()};
  v.vignetting.kind = VignettingKind::Cos4;
  pushPostProcessor(L, std::move(v));
  return 1;
}

int vignettingRadial(lua_State* L) {
  Params p(L, "Vignetting.Radial", {"coefficients"});
  PostProcessorValue v{PostProcessorValue::Kind::Vignetting, p.constructor()};
  v.vignetting.kind = VignettingKind::Radial;
  auto c = p.numbers("coefficients", 1, 3, "{a1[, a2[, a3]]}");
  if (!c) p.fail("missing required 'coefficients' = {a1[, a2[, a3]]}");
  v.vignetting.coefficients = *c;
  pushPostProcessor(L, std::move(v));
  return 1;
}

/* Dust { center_px = {x, y}; radius_px; opacity }: one soft dark blob (all required);
   radius_px > 0, opacity in [0, 1]. */
int dust(lua_State* L) {
  Params p(L, "Dust", {"center_px", "radius_px", "opacity"});
  PostProcessorValue v{PostProcessorValue::Kind::Dust, p.constructor()};
  auto centre = p.vec2("center_px", "{x, y}");
  if (!centre) p.fail("missing required 'center_px' = {x, y} (px)");
  v.dust.x_px = centre->x;
  v.dust.y_px = centre->y;
  v.dust.radius_px = p.requiredNumber("radius_px");
  p.require(v.dust.radius_px > 0, "radius_px", "> 0 (px)", v.dust.radius_px);
  v.dust.opacity = p.requiredNumber("opacity");
  p.require(v.dust.opacity >= 0 && v.dust.opacity <= 1, "opacity", "in [0, 1]", v.dust.opacity);
  pushPostProcessor(L, std::move(v));
  return 1;
}

// A list of pixels {{x, y}, ...} (integers >= 0), or a fraction (a number in [0, 1]).
void readDefectKind(lua_State* L, const Params& p, const char* key, double& fraction,
                    std::vector<PixelPosition>& list) {
  const int type = p.luaType(key);
  if (type == LUA_TNIL) return;
  if (type == LUA_TNUMBER) {
    fraction = *p.number(key);
    p.require(fraction >= 0 && fraction <= 1, key, "a fraction in [0, 1] or a list {{x, y}, ...}", fraction);
    return;
  }
  const std::string expected = Params::quote(key) + " must be a fraction in [0, 1] or a list {{x, y}, ...} of pixels";
  if (type != LUA_TTABLE) p.fail(expected);
  lua_pushstring(L, key);
  lua_rawget(L, 1);
  const int table = lua_gettop(L);
  const lua_Integer count = lua_Integer(lua_rawlen(L, table));
  lua_Integer entries = 0;
  lua_pushnil(L);
  while (lua_next(L, table) != 0) {
    lua_pop(L, 1);
    ++entries;
  }
  bool ok = entries == count;
  for (lua_Integer i = 1; ok && i <= count; ++i) {
    lua_rawgeti(L, table, i);
    const int pixel = lua_gettop(L);
    double xy[2] = {-1, -1};
    ok = lua_istable(L, pixel) && lua_rawlen(L, pixel) == 2;
    for (int c = 0; ok && c < 2; ++c) {
      lua_rawgeti(L, pixel, c + 1);
      ok = lua_type(L, -1) == LUA_TNUMBER;
      if (ok) xy[c] = lua_tonumber(L, -1);
      lua_pop(L, 1);
      ok = ok && xy[c] == std::floor(xy[c]) && xy[c] >= 0 && xy[c] <= 65535;
    }
    lua_pop(L, 1);
    if (ok) list.push_back({int(xy[0]), int(xy[1])});
    else {
      lua_pop(L, 1);
      p.fail(expected + "; entry " + std::to_string(i) + " is not {x, y} with integers in 0..65535");
    }
  }
  lua_pop(L, 1);
  if (!ok) p.fail(expected + ", got a table with named or missing entries");
}

/* DefectivePixels { dead; hot; stuck; seed; hotSignal_DN; stuck_DN } (see docs/sensor.md):
   dead, hot, stuck: each a fraction of the pixels in [0, 1] (drawn from the seed) or a list of
   pixels {{x, y}, ...}; default 0. seed: integer, default the render's --seed. hotSignal_DN: added
   to hot pixels (default floor((2^b - 1)/4)); stuck_DN: value of stuck pixels (default 2^b - 1). */
int defectivePixels(lua_State* L) {
  Params p(L, "DefectivePixels", {"dead", "hot", "stuck", "seed", "hotSignal_DN", "stuck_DN"});
  PostProcessorValue v{PostProcessorValue::Kind::Defects, p.constructor()};
  DefectivePixels& d = v.defects;
  readDefectKind(L, p, "dead", d.deadFraction, d.dead);
  readDefectKind(L, p, "hot", d.hotFraction, d.hot);
  readDefectKind(L, p, "stuck", d.stuckFraction, d.stuck);
  const double total = d.deadFraction + d.hotFraction + d.stuckFraction;
  if (total > 1) p.fail("the fractions dead + hot + stuck must not exceed 1, got " + formatNumber(total));
  if (auto seed = p.integer("seed")) {
    p.require(*seed >= 0 && *seed <= 0xffffffffLL, "seed", "an integer in 0..4294967295", double(*seed));
    d.seed = std::uint32_t(*seed);
  }
  d.hotSignal_DN = p.number("hotSignal_DN");
  if (d.hotSignal_DN)
    p.require(*d.hotSignal_DN >= 0 && *d.hotSignal_DN <= 65535, "hotSignal_DN", "in 0..65535 (DN)", *d.hotSignal_DN);
  d.stuck_DN = p.number("stuck_DN");
  if (d.stuck_DN) p.require(*d.stuck_DN >= 0 && *d.stuck_DN <= 65535, "stuck_DN", "in 0..65535 (DN)", *d.stuck_DN);
  pushPostProcessor(L, std::move(v));
  return 1;
}

int sensorToString(lua_State* L) {
  const EmvaSensor* s = toUserdata<EmvaSensor>(L, 1);
  const std::string text = "Sensor.Emva(" + (s ? s->preset : std::string()) + ")";
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

int postProcessorToString(lua_State* L) {
  const PostProcessorValue* v = toUserdata<PostProcessorValue>(L, 1);
  const std::string text = v ? v->constructor : std::string("PostProcessor");
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

void setGlobalFunction(lua_State* L, const char* name, lua_CFunction f) {
  lua_pushcfunction(L, f);
  lua_setglobal(L, name);
}

}  // namespace

void readCameraSensor(lua_State* L, const Params& p, Camera& camera) {
  SensorModel& m = camera.sensor;
  if (const EmvaSensor* s = p.userdata<EmvaSensor>("sensor", "a Sensor (Sensor.Emva { ... })")) {
    m.emva = *s;
    // A black level at or above full scale leaves the signal no range: every pixel would read full
    // scale (and the default gain, which maps the well onto the range above the offset, be <= 0).
    const double fullScale = double((1u << camera.bitsPerPixel) - 1u);
    if (s->darkOffset_DN && *s->darkOffset_DN >= fullScale)
      p.fail("'sensor': darkOffset_DN = " + formatNumber(*s->darkOffset_DN) + " leaves no range for the signal: " +
             "it must be below the full scale 2^bitsPerPixel - 1 = " + formatNumber(fullScale) + " DN");
  }
  const int type = p.luaType("postProcessing");
  if (type == LUA_TNIL) return;
  const char* expected = "'postProcessing' must be a list {Blur..., Vignetting..., Dust {...}, DefectivePixels {...}}";
  if (type != LUA_TTABLE) p.fail(expected);
  lua_pushstring(L, "postProcessing");
  lua_rawget(L, 1);
  const int table = lua_gettop(L);
  const lua_Integer count = lua_Integer(lua_rawlen(L, table));
  // Collect the values first (copies), so that the Lua stack is balanced before any failure.
  std::vector<PostProcessorValue> values;
  lua_Integer entries = 0;
  lua_pushnil(L);
  while (lua_next(L, table) != 0) {
    lua_pop(L, 1);
    ++entries;
  }
  const bool sequence = entries == count;
  std::string bad;
  for (lua_Integer i = 1; sequence && bad.empty() && i <= count; ++i) {
    lua_rawgeti(L, table, i);
    if (const PostProcessorValue* v = toUserdata<PostProcessorValue>(L, -1)) values.push_back(*v);
    else bad = "entry " + std::to_string(i) + " is a " + typeName(L, -1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (!sequence) p.fail(std::string(expected) + ", got a table with named or missing entries");
  if (!bad.empty()) p.fail(std::string(expected) + "; " + bad);

  // The checks that need the camera run here, under the camera's constructor; each names the
  // entry's own line too (the camera's line alone pointed several lines away from the mistake).
  int blurLine = 0, vignettingLine = 0, defectsLine = 0;
  const double fullScale_DN = double((1u << camera.bitsPerPixel) - 1u);
  for (const PostProcessorValue& v : values) {
    const std::string entry = v.constructor + " (line " + std::to_string(v.line) + ")";
    auto once = [&](int& firstLine, const char* what) {
      if (firstLine != 0)
        p.fail("'postProcessing' has more than one " + std::string(what) + " (lines " + std::to_string(firstLine) +
               " and " + std::to_string(v.line) + ")");
      firstLine = v.line;
    };
    switch (v.kind) {
      case PostProcessorValue::Kind::Blur:
        once(blurLine, "Blur");
        m.blur = v.blur;
        break;
      case PostProcessorValue::Kind::Vignetting:
        once(vignettingLine, "Vignetting");
        if (v.vignetting.kind == VignettingKind::Cos4 && camera.kindInfo().telecentric)
          p.fail(entry + ": a telecentric (orthographic) camera's chief rays are parallel to the axis, so it "
                 "has no cos⁴ fall-off; use Vignetting.Radial");
        m.vignetting = v.vignetting;
        break;
      case PostProcessorValue::Kind::Dust: {
        // A blob that reaches no pixel centre changes nothing: most likely a position in other
        // units or of another image. The nearest pixel centre is the clamped, rounded centre.
        const double nearestX = std::clamp(std::round(v.dust.x_px), 0.0, double(camera.width_px - 1));
        const double nearestY = std::clamp(std::round(v.dust.y_px), 0.0, double(camera.height_px - 1));
        if (std::hypot(v.dust.x_px - nearestX, v.dust.y_px - nearestY) >= v.dust.radius_px)
          p.fail(entry + ": the blob at {" + formatNumber(v.dust.x_px) + ", " + formatNumber(v.dust.y_px) +
                 "} px of radius " + formatNumber(v.dust.radius_px) + " px reaches no pixel of the " +
                 std::to_string(camera.width_px) + "x" + std::to_string(camera.height_px) +
                 " image (pixel centres 0.." + std::to_string(camera.width_px - 1) + ", 0.." +
                 std::to_string(camera.height_px - 1) + "): it would change nothing");
        m.dust.push_back(v.dust);
        break;
      }
      case PostProcessorValue::Kind::Defects:
        once(defectsLine, "DefectivePixels");
        for (const auto* list : {&v.defects.dead, &v.defects.hot, &v.defects.stuck})
          for (const PixelPosition& px : *list)
            if (px.x_px >= camera.width_px || px.y_px >= camera.height_px)
              p.fail(entry + ": pixel {" + std::to_string(px.x_px) + ", " + std::to_string(px.y_px) +
                     "} is outside the " + std::to_string(camera.width_px) + "x" + std::to_string(camera.height_px) +
                     " image");
        // A stuck pixel reads its value as the sensor's output: above full scale it could not.
        if (v.defects.stuck_DN && *v.defects.stuck_DN > fullScale_DN)
          p.fail(entry + ": stuck_DN = " + formatNumber(*v.defects.stuck_DN) + " is above the full scale 2^" +
                 std::to_string(camera.bitsPerPixel) + " - 1 = " + formatNumber(fullScale_DN) +
                 " DN of this camera's bitsPerPixel");
        m.defects = v.defects;
        break;
    }
  }
}

void registerSensorConstructors(lua_State* L) {
  registerUserdataType<EmvaSensor>(L, {{"__tostring", &sensorToString}});
  registerUserdataType<PostProcessorValue>(L, {{"__tostring", &postProcessorToString}});
  setConstructorTable(L, "Sensor", {{"Emva", &protectedCall<sensorEmva>}});
  setConstructorTable(L, "Blur", {{"Gaussian", &protectedCall<blurGaussian>}, {"Disk", &protectedCall<blurDisk>}});
  setConstructorTable(L, "Vignetting",
                      {{"Cos4", &protectedCall<vignettingCos4>}, {"Radial", &protectedCall<vignettingRadial>}});
  setGlobalFunction(L, "Dust", &protectedCall<dust>);
  setGlobalFunction(L, "DefectivePixels", &protectedCall<defectivePixels>);
}

}  // namespace dicsynth::scene
