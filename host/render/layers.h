#pragma once
// The outputs a run writes (`--layers`): the sensor image and named groups of ground-truth
// channels. A layer not asked for is not derived (the CPU-traced visibility of flow and disparity,
// the distortion field), not converted on readback (P, N, uv, depth), and not stored; with no
// ground-truth layer at all no EXR is written. The list is closed: one enum value, one name, its
// channels (README, "Output layers").
//   layer       file / EXR channels
//   image       <stem>.tif, the sensor image (digital numbers)
//   radiance    Y
//   depth       Z
//   P           P.X P.Y P.Z
//   normal      N.X N.Y N.Z
//   uv          uv.U uv.V
//   mask        objectId mask
//   disp        disp.X disp.Y disp.Z
//   flow        flow.X flow.Y flow.mask
//   disparity   disparity.X disparity.Y disparity.mask   (cameras of a stereo rig)
//   distortion  distortion.X distortion.Y
//   noise       noiseFree noise                           (cameras with a sensor model)
//   defects     defects                                   (cameras with DefectivePixels)
//   fieldError  fieldError.X fieldError.Y fieldError.Z    (frames with a Nurbs.deform surface)
// `all` is every layer the scene can produce: the default, so that a run without --layers keeps the
// complete ground truth the tool exists for.
#include <cstdint>
#include <string>
#include <vector>

namespace dicsynth {

struct Scene;

enum class Layer : std::uint32_t {
  Image, Radiance, Depth, P, Normal, Uv, Mask, Disp, Flow, Disparity, Distortion, Noise, Defects, FieldError,
  Count
};

class LayerSet {
 public:
  LayerSet() = default;
  static LayerSet all();
  // "all" or a comma-separated list of layer names. Throws InputError naming `option` and the
  // unknown name, with the list of known ones.
  static LayerSet parse(const std::string& text, const std::string& option = "--layers");

  bool has(Layer layer) const { return (bits_ >> std::uint32_t(layer)) & 1u; }
  LayerSet& add(Layer layer) {
    bits_ |= 1u << std::uint32_t(layer);
    return *this;
  }
  bool isAll() const { return all_; }
  bool empty() const { return bits_ == 0; }
  // Any EXR channel: the ground-truth file is written.
  bool anyGroundTruth() const { return (bits_ & ~(1u << std::uint32_t(Layer::Image))) != 0; }
  // The backend must hand back P, N, uv and depth (directly asked, or needed to derive motion and
  // disparity from material points).
  bool needsGeometry() const;
  // The backend must trace the sample rays (image, radiance, noise, defects); otherwise only the
  // pixel-centre ground-truth ray is traced.
  bool needsRadiance() const;
  // The names, in the enum's order, comma-separated; "all" for all().
  std::string text() const;

 private:
  std::uint32_t bits_ = 0;
  bool all_ = false;  // "all": layers the scene cannot produce are skipped, not an error
};

const char* layerName(Layer layer);

// What of the scenes of a run decides which layers it can produce, gathered frame by frame.
struct LayerSources {
  bool rig = false, sensor = false, defects = false, deformed = false;
  void add(const Scene& scene);
};
void checkLayersProducible(const LayerSet& layers, const LayerSources& sources, const std::string& option = "--layers");

// Throws InputError when `layers` names a layer that no camera of any of `scenes` can produce
// (disparity without a stereo rig, noise without a sensor model, defects without DefectivePixels,
// fieldError without a Nurbs.deform surface).
void checkLayersProducible(const LayerSet& layers, const std::vector<Scene>& scenes, const std::string& option = "--layers");

}  // namespace dicsynth
