#pragma once
// The outputs a run writes (`--layers`): the sensor image and named groups of ground-truth
// channels. A layer not asked for is not derived (the visibility of flow and disparity, the
// distortion field), not converted on readback (P, N, uv, depth), and not stored; with no
// ground-truth layer at all no EXR is written. The list is closed: one enum value and one row of
// the schema (layers.cpp kSpecs: name, channels, what the backend must trace, which scenes can
// produce it); docs/outputs.md's table is checked against it.
// `all` is every layer the scene can produce: the default, so that a run without --layers keeps the
// complete ground truth the tool exists for.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/option_names.h"

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
  static LayerSet parse(const std::string& text, const std::string& option = optionName("--layers"));

  bool has(Layer layer) const { return (bits_ >> std::uint32_t(layer)) & 1u; }
  LayerSet& add(Layer layer) {
    bits_ |= 1u << std::uint32_t(layer);
    return *this;
  }
  bool isAll() const { return all_; }
  bool empty() const { return bits_ == 0; }
  // Any EXR channel: the ground-truth file is written.
  bool anyGroundTruth() const { return (bits_ & ~(1u << std::uint32_t(Layer::Image))) != 0; }
  // A layer measured from the reference frame (disp, flow, fieldError): what needs the reference
  // frame's material points (render/ground_truth.cpp), and what a folder's earlier reference frame
  // matters to (job/render_job.cpp).
  bool anyMotion() const { return has(Layer::Disp) || has(Layer::Flow) || has(Layer::FieldError); }
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

// The schema of the layers: one row per Layer (layers.cpp), which parsing, the backends' needs,
// the producibility check, the GPU readback (gpu/renderer.cpp), the EXR writer's channel names and
// types (io/outputs.cpp), the comparison's report (cli/compare.cpp) and the docs' channel tables
// (tests/suite/test_docs.cpp) all read.
enum class LayerSource : std::uint8_t {
  Always,    // every camera of every scene
  Rig,       // cameras of a stereo rig (Rig.Stereo)
  Sensor,    // cameras with a sensor model (Sensor.Emva or post-processors)
  Defects,   // cameras with DefectivePixels
  Deformed,  // frames with a Nurbs.deform surface
};
// Where the GPU backend hands a traced value back: a component of render.comp's GpuPixel
// (shaders/shared/gpu_types.h). The other layers are computed on the host from these.
enum class GpuSlot : std::uint8_t {
  None,
  Radiance,  // uvRadianceId.z: mean radiance over the samples
  ObjectId,  // uvRadianceId.w: 0 background, else the object's index + 1 (an exact small integer)
  Position,  // positionDepth.xyz: world P, camera-relative (the camera centre goes back in, in double)
  Depth,     // positionDepth.w
  Uv,        // uvRadianceId.xy
  Normal,    // normal.xyz
};

// How `dicsynth compare` (render/compare.h) judges a layer of the GPU against the CPU reference.
enum class Comparison : std::uint8_t {
  Radiance,  // |ΔL| within the per-pixel radiance bound (shading, texture slope, specular terms)
  Position,  // |ΔP| within the per-pixel position bound (conditioned on the viewing angle); |ΔZ| reported
  Uv,        // |Δuv| within the per-pixel uv bound
  Normal,    // |ΔN| reported; fp64 within 1e-9 (the float variants compute normals in float)
  Exact,     // equal: every difference is a wrong nearest hit, counted by kind
  Derived,   // computed on the host in double from P, uv, material points or the camera model: judged
             // through those
  Sensor,    // computed on the host from the radiance and the seed: judged through the radiance
};
const char* comparisonName(Comparison comparison);  // as docs/outputs.md and compare --json name it

struct LayerChannel {
  const char* name = nullptr;  // EXR channel name
  bool uint32 = false;         // exact 32-bit integers; otherwise float32
};
struct LayerSpec {
  Layer layer;
  const char* name;      // the --layers name
  std::array<LayerChannel, 3> channels;  // in file order; unused entries have no name ("image": none, the TIFF)
  bool geometry;         // needs the backend's P, N, uv and depth (asked, or to derive from material points)
  bool radiance;         // needs the sample rays (otherwise only the pixel-centre ray is traced)
  LayerSource source;
  const char* without;   // when `source` is missing: why the layer cannot be produced
  GpuSlot gpu;           // where the GPU backend returns it (None: derived on the host)
  Comparison compare;    // how the comparison of backends judges it
};
const LayerSpec& layerSpec(Layer layer);
std::span<const LayerSpec> layerSpecs();
const char* layerName(Layer layer);

// What of the scenes of a run decides which layers it can produce, gathered frame by frame.
struct LayerSources {
  bool rig = false, sensor = false, defects = false, deformed = false;
  void add(const Scene& scene);
  bool provides(LayerSource source) const;
};
void checkLayersProducible(const LayerSet& layers, const LayerSources& sources, const std::string& option = optionName("--layers"));

// Throws InputError when `layers` names a layer that no camera of any of `scenes` can produce
// (disparity without a stereo rig, noise without a sensor model, defects without DefectivePixels,
// fieldError without a Nurbs.deform surface).
void checkLayersProducible(const LayerSet& layers, const std::vector<Scene>& scenes, const std::string& option = optionName("--layers"));

}  // namespace dicsynth
