#include "render/layers.h"

#include <iterator>

#include "core/error.h"
#include "model/scene.h"

namespace dicsynth {

namespace {

constexpr const char* kNames[] = {"image", "radiance", "depth", "P", "normal", "uv", "mask",
                                  "disp", "flow", "disparity", "distortion", "noise", "defects",
                                  "fieldError"};
static_assert(std::size(kNames) == std::size_t(Layer::Count), "one name per layer");

std::string knownNames() {
  std::string list = "all";
  for (const char* name : kNames) list += std::string(", ") + name;
  return list;
}

}  // namespace

const char* layerName(Layer layer) { return kNames[std::size_t(layer)]; }

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
      if (name == kNames[l]) {
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
  for (Layer l : {Layer::Depth, Layer::P, Layer::Normal, Layer::Uv, Layer::Disp, Layer::Flow, Layer::Disparity,
                  Layer::FieldError})
    if (has(l)) return true;
  return false;
}

bool LayerSet::needsRadiance() const {
  for (Layer l : {Layer::Image, Layer::Radiance, Layer::Noise, Layer::Defects})
    if (has(l)) return true;
  return false;
}

std::string LayerSet::text() const {
  if (all_) return "all";
  std::string out;
  for (std::uint32_t l = 0; l < std::uint32_t(Layer::Count); ++l)
    if (has(Layer(l))) out += (out.empty() ? "" : ",") + std::string(kNames[l]);
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

void checkLayersProducible(const LayerSet& layers, const LayerSources& sources, const std::string& option) {
  if (layers.isAll()) return;
  auto refuse = [&](Layer layer, const std::string& why) {
    throw InputError(option + ": layer '" + layerName(layer) + "' cannot be produced: " + why);
  };
  if (layers.has(Layer::Disparity) && !sources.rig) refuse(Layer::Disparity, "no camera of the scene belongs to a stereo rig (Rig.Stereo)");
  if (layers.has(Layer::Noise) && !sources.sensor) refuse(Layer::Noise, "no camera of the scene has a sensor model (a camera's sensor = Sensor.Emva { ... } or postProcessing)");
  if (layers.has(Layer::Defects) && !sources.defects)
    refuse(Layer::Defects, "no camera of the scene has defective pixels (DefectivePixels { ... } in a camera's postProcessing)");
  if (layers.has(Layer::FieldError) && !sources.deformed)
    refuse(Layer::FieldError, "no object of the scene has a Nurbs.deform surface in any frame rendered");
}

void checkLayersProducible(const LayerSet& layers, const std::vector<Scene>& scenes, const std::string& option) {
  LayerSources sources;
  for (const Scene& scene : scenes) sources.add(scene);
  checkLayersProducible(layers, sources, option);
}

}  // namespace dicsynth
