#pragma once
// The CPU reference renderer: double precision, multithreaded over image rows, the same samples as
// the GPU (camera/sampling.h). It is the truth every GPU result is compared with.
#include "geometry/prepared_scene.h"
#include "model/render_options.h"
#include "model/render_result.h"

namespace dicsynth::cpu {

// Renders every camera. options.precision is ignored (always double).
RenderResult render(const PreparedScene& scene, const RenderOptions& options);

}  // namespace dicsynth::cpu
