#pragma once
// Ground truth derived from the renders, per camera and frame: the motion of the material since the
// reference frame (disp, flow), the stereo correspondence to the rig's other camera (disparity) and
// the lens distortion of every pixel. Written to the .exr beside the backend's own layers
// (io/outputs.h); docs/outputs.md's table of channels documents channels, units and conventions.
//
// Every value is a difference computed in double from material points (geometry/material_point.h):
// disp = P_k(m) − P_ref(m), flow = x_k(m) − x_ref(m), disparity = x_other(m) − x_this(m), where m
// is the material point the backend found at the pixel centre. Computing both ends from m (instead
// of subtracting the pixel centre) means the backend's error in finding m (its geometric error,
// ≤ the precision's bound) enters only multiplied by the field's gradient, i.e. the strain:
// a 1e-6 px error in m moves a flow of strain 1e-2 by 1e-8 px. Float32 storage then limits each
// value to a relative 2^-24 of its magnitude, e.g. 3e-5 px for a 500 px disparity.
//
// Visibility (the masks) is traced in double by the CPU reference (cpu::traceNearest): a material
// point is visible in a camera when it lies in front of it, projects inside the image (pixel
// centres' square [−0.5, w − 0.5] × [−0.5, h − 0.5]) through a distortion that is invertible there,
// and the ray from the camera centre towards it first meets its own object within 1e-6 of the
// distance (0.5 µm at 0.5 m: far closer than any occluder a scene can mean, far looser than the
// 1e-12 relative accuracy of the traced hit), on the side of the surface the reference pixel saw
// (sideSeen, geometry/material_point.h: the other side of a zero-thickness surface is another
// face of the specimen).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "geometry/prepared_scene.h"
#include "model/render_result.h"
#include "model/layers.h"
#include "render/visibility.h"

namespace dicsynth {

struct DerivedTruth {
  // Motion since the reference frame, indexed by the REFERENCE image's pixels (Lagrangian, as DIC
  // reports displacements at reference subset centres). NaN where the reference pixel sees no
  // object, or its object is absent from this frame. Empty when the camera has no reference view
  // (absent from the reference frame or with another resolution there).
  int referenceFrame = 0;
  std::vector<dvec3> displacement_m;  // disp.X/Y/Z: world displacement (m)
  std::vector<dvec2> flow_px;         // flow.X/Y: image motion (px, this frame's camera model)
  std::vector<float> flowMask;        // flow.mask: 1 where the material point is visible now
  // fieldError.X/Y/Z (m, world axes), reference pixels: where the material point is rendered minus
  // where the requested field puts it, T(F(m)) − T(S(m) + d(S(m))), for an object whose surface is
  // a Nurbs.deform fit F of S moved by d (T: the object's transform in this frame); 0 for other
  // objects (rendered as requested), NaN where disp is. Empty when no object of this frame is a fit.
  std::vector<dvec3> fieldError_m;
  // Correspondence to the other camera of the rig this camera belongs to, indexed by THIS image's
  // pixels. NaN where this pixel sees no object. Empty when the camera is in no rig.
  std::string disparityCamera;
  std::vector<dvec2> disparity_px;    // disparity.X/Y (px)
  std::vector<float> disparityMask;   // disparity.mask: 1 where the other camera sees the point
  std::size_t disparityVisibleCount = 0;
  // distortion.X/Y: distorted minus undistorted image position of every pixel centre (px);
  // zero for a camera without distortion. Shared with the fields kept for the next frames and sweep
  // points (distortionField in ground_truth.cpp), not copied; null when the layer is not asked for.
  std::shared_ptr<const std::vector<dvec2>> distortion_px;
  const std::vector<dvec2>& distortion() const {  // *distortion_px, or empty
    static const std::vector<dvec2> none;
    return distortion_px ? *distortion_px : none;
  }
};

// What the motion truth keeps of the reference frame: its scene and, per camera, the material
// point the backend found at each pixel centre.
class ReferenceFrame {
 public:
  // `otherFrames` false: only the reference frame itself will be derived (a single-frame render, every
  // sweep point), so the projections x_ref(m), which only other frames' flow uses, are not computed
  // (a distortion inversion per pixel in projectToImage's fold test; its share of a sweep point's
  // CPU is in bench/RESULTS.md, "Sweeps"). Nor, unless an object is deformed (fieldError reads
  // them), the material coordinates and points: the reference frame's own disp and flow are zero
  // wherever a material point exists, which is all `object` has to say (Figure 1's truth phase:
  // 0.17 → 0.14 s; bench/RESULTS.md, "a lighter reference frame").
  // `motion` false: no layer derived from it is asked for (--layers without disp and flow): it only
  // keeps the scene, and deriveTruth finds no view.
  ReferenceFrame(int frame, PreparedScene scene, const RenderResult& result, bool otherFrames = true,
                 bool motion = true);
  int frame() const { return frame_; }

  struct View {
    std::string camera;
    int width_px = 0, height_px = 0;
    std::vector<int> object;       // index into scene().objects, −1 for background (or no material point)
    std::vector<dvec2> material;   // material coordinates (geometry/material_point.h) (empty: see the constructor)
    std::vector<dvec3> position_m; // P_ref(m), recomputed in double from the material coordinates (empty: likewise)
    std::vector<dvec2> pixel_px;   // x_ref(m): its projection into the reference camera (empty: !otherFrames)
    std::vector<std::int8_t> side;  // the side of the surface the reference camera sees there (sideSeen,
                                    // geometry/material_point.h; empty: likewise)
  };
  const View* view(const std::string& camera) const;
  const PreparedScene& scene() const { return scene_; }

 private:
  int frame_;
  PreparedScene scene_;
  std::vector<View> views_;
};

// The derived layers of camera `camera` (index into scene.cameras and result.cameras) of frame
// `frame`. For the reference frame itself disp = flow = 0 and flow.mask = 1 wherever the reference
// pixel sees an object (it is visible there by construction), without tracing.
// Only the layers in `layers` are derived: without flow no visibility is traced for it, without
// disparity nothing is projected into the other camera, without distortion no field is computed.
// `visibility`: who traces the visibility of flow.mask and disparity.mask (render/visibility.h);
// empty: the CPU reference.
DerivedTruth deriveTruth(const ReferenceFrame& reference, int frame, const PreparedScene& scene,
                         const RenderResult& result, std::size_t camera, const LayerSet& layers = LayerSet::all(),
                         const VisibilityTracer& visibility = {});

}  // namespace dicsynth
