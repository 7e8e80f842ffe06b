#include "model/layers.h"

#include <iterator>

#include "core/error.h"
#include "model/scene.h"

namespace dicsynth {

namespace {

constexpr LayerChannel F(const char* name) { return {name, false}; }
constexpr LayerChannel U(const char* name) { return {name, true}; }
using C = std::array<LayerChannel, 3>;
constexpr LayerSource A = LayerSource::Always;
using S = GpuSlot;
using K = Comparison;

// Rows in the enum's order (checked below).
constexpr LayerSpec kSpecs[] = {
    {Layer::Image, "image", C{}, false, true, A, "", S::Radiance, K::Radiance},
    {Layer::Radiance, "radiance", C{F("Y")}, false, true, A, "", S::Radiance, K::Radiance},
    {Layer::Depth, "depth", C{F("Z")}, true, false, A, "", S::Depth, K::Position},
    {Layer::P, "P", C{F("P.X"), F("P.Y"), F("P.Z")}, true, false, A, "", S::Position, K::Position},
    {Layer::Normal, "normal", C{F("N.X"), F("N.Y"), F("N.Z")}, true, false, A, "", S::Normal, K::Normal},
    {Layer::Uv, "uv", C{F("uv.U"), F("uv.V")}, true, false, A, "", S::Uv, K::Uv},
    {Layer::Mask, "mask", C{U("objectId"), F("mask")}, false, false, A, "", S::ObjectId, K::Exact},
    {Layer::Disp, "disp", C{F("disp.X"), F("disp.Y"), F("disp.Z")}, true, false, A, "", S::None, K::Derived},
    {Layer::Flow, "flow", C{F("flow.X"), F("flow.Y"), F("flow.mask")}, true, false, A, "", S::None, K::Derived},
    {Layer::Disparity, "disparity", C{F("disparity.X"), F("disparity.Y"), F("disparity.mask")}, true, false,
     LayerSource::Rig, "no camera of the scene belongs to a stereo rig (Rig.Stereo)", S::None, K::Derived},
    {Layer::Distortion, "distortion", C{F("distortion.X"), F("distortion.Y")}, false, false, A, "", S::None,
     K::Derived},
    {Layer::Noise, "noise", C{F("noiseFree"), F("noise")}, false, true, LayerSource::Sensor,
     "no camera of the scene has a sensor model (a camera's sensor = Sensor.Emva { ... } or postProcessing)", S::None,
     K::Sensor},
    {Layer::Defects, "defects", C{U("defects")}, false, true, LayerSource::Defects,
     "no camera of the scene has defective pixels (DefectivePixels { ... } in a camera's postProcessing)", S::None,
     K::Sensor},
    {Layer::FieldError, "fieldError", C{F("fieldError.X"), F("fieldError.Y"), F("fieldError.Z")}, true, false,
     LayerSource::Deformed, "no object of the scene has a Nurbs.deform surface in any frame rendered", S::None,
     K::Derived},
};
static_assert(std::size(kSpecs) == std::size_t(Layer::Count), "one row per layer");
constexpr bool inEnumOrder() {
  for (std::size_t i = 0; i < std::size(kSpecs); ++i)
    if (kSpecs[i].layer != Layer(i)) return false;
  return true;
}
static_assert(inEnumOrder(), "kSpecs rows in the enum's order");

std::string knownNames() {
  std::string list = "all";
  for (const LayerSpec& spec : kSpecs) list += std::string(", ") + spec.name;
  return list;
}

}  // namespace

const LayerSpec& layerSpec(Layer layer) { return kSpecs[std::size_t(layer)]; }
std::span<const LayerSpec> layerSpecs() { return kSpecs; }
const char* layerName(Layer layer) { return layerSpec(layer).name; }

const char* comparisonName(Comparison comparison) {
  switch (comparison) {
    case Comparison::Radiance: return "radiance bound";
    case Comparison::Position: return "position bound";
    case Comparison::Uv: return "uv bound";
    case Comparison::Normal: return "normal";
    case Comparison::Exact: return "exact";
    case Comparison::Derived: return "derived";
    case Comparison::Sensor: return "sensor";
  }
  return "?";
}

LayerSet LayerSet::all() {
  LayerSet s;
  for (std::uint32_t l = 0; l < std::uint32_t(Layer::Count); ++l) s.add(Layer(l));
  s.all_ = true;
  return s;
}

LayerSet LayerSet::parse(const std::string& text, const std::string& option) {
  if (text == "all") return all();
  LayerSet s;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string name = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (name.empty())
      throw InputError(option + " " + text + ": an empty layer name (expected a comma-separated list of: " +
                       knownNames() + ")");
    if (name == "all") throw InputError(option + " " + text + ": 'all' stands alone, not in a list");
    bool found = false;
    for (std::uint32_t l = 0; l < std::uint32_t(Layer::Count); ++l)
      if (name == kSpecs[l].name) {
        s.add(Layer(l));
        found = true;
      }
    if (!found) throw InputError(option + " " + text + ": unknown layer '" + name + "' (known: " + knownNames() + ")");
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return s;
}

bool LayerSet::needsGeometry() const {
  for (const LayerSpec& spec : kSpecs)
    if (spec.geometry && has(spec.layer)) return true;
  return false;
}

bool LayerSet::needsRadiance() const {
  for (const LayerSpec& spec : kSpecs)
    if (spec.radiance && has(spec.layer)) return true;
  return false;
}

std::string LayerSet::text() const {
  if (all_) return "all";
  std::string out;
  for (std::uint32_t l = 0; l < std::uint32_t(Layer::Count); ++l)
    if (has(Layer(l))) {
      if (!out.empty()) out += ',';
      out += kSpecs[l].name;
    }
  return out;
}

void LayerSources::add(const Scene& scene) {
  rig = rig || !scene.rigs.empty();
  for (const Object& object : scene.objects) deformed = deformed || object.shape.deformation != nullptr;
  for (const Camera& camera : scene.cameras) {
    sensor = sensor || !camera.sensor.empty();
    defects = defects || camera.sensor.defects.has_value();
  }
}

bool LayerSources::provides(LayerSource source) const {
  switch (source) {
    case LayerSource::Always: return true;
    case LayerSource::Rig: return rig;
    case LayerSource::Sensor: return sensor;
    case LayerSource::Defects: return defects;
    case LayerSource::Deformed: return deformed;
  }
  return false;
}

void checkLayersProducible(const LayerSet& layers, const LayerSources& sources, const std::string& option) {
  if (layers.isAll()) return;
  for (const LayerSpec& spec : kSpecs) {
    if (!layers.has(spec.layer)) continue;
    if (!sources.provides(spec.source))
      throw InputError(option + ": layer '" + spec.name + "' cannot be produced: " + spec.without);
  }
}

void checkLayersProducible(const LayerSet& layers, const std::vector<Scene>& scenes, const std::string& option) {
  LayerSources sources;
  for (const Scene& scene : scenes) sources.add(scene);
  checkLayersProducible(layers, sources, option);
}

}  // namespace dicsynth
