#pragma once
// The visibility behind the masks of flow and disparity: whether the chief ray of a camera towards a
// point first meets the point's own object, at the point (render/image_point.h reachesFirst, relative
// tolerance on the ray parameter, the point at t = 1). deriveTruth (render/ground_truth.h) asks for
// all points of one camera and layer at once, so that the device that rendered can trace them in one
// pass (gpu::Renderer::reachesFirst, bound into a VisibilityTracer by the render job); without a
// tracer the CPU reference traces them, one double-precision ray per point.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/math.h"
#include "geometry/prepared_scene.h"

namespace dicsynth {

// The ray towards a visible point first meets the point's own object within this fraction of the
// distance (docs/outputs.md, "Visibility").
inline constexpr double kVisibilityTolerance = 1e-6;

// 1 where points_m[i] is reached first on objects[i] (an index into scene.objects), else 0.
using VisibilityTracer = std::function<std::vector<std::uint8_t>(
    const PreparedScene& scene, std::size_t camera, std::span<const dvec3> points_m, std::span<const int> objects,
    double relativeTolerance)>;

// The CPU reference's answer: reachesFirst per point, in double, points in parallel.
std::vector<std::uint8_t> reachesFirstCpu(const PreparedScene& scene, std::size_t camera, std::span<const dvec3> points_m,
                                          std::span<const int> objects, double relativeTolerance);

}  // namespace dicsynth
