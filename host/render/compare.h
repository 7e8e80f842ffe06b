#pragma once
// Comparison of two renders of the same prepared scene (CPU reference vs GPU), computed in double,
// and the documented tolerances each GPU precision is held to.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/prepared_scene.h"
#include "model/layers.h"
#include "model/render_options.h"
#include "model/render_result.h"
#include "render/visibility.h"

namespace dicsynth {

struct CameraDifference {
  std::string camera;
  std::size_t pixels = 0;
  // Radiance as a fraction of full scale (radiance × exposure): what the sensor would see.
  double maxRadianceDiff = 0;
  double rmsRadianceDiff = 0;
  // Worst radiance difference over its per-pixel bound (≤ 1: fine): Tolerances::radiance of full
  // scale, relative above full scale, plus (fp32, df64) the derived shading terms, which grow as a
  // light nears a surface. maxRadianceDiff alone can read as a failure where the bound is wide
  // (8e27 beside a lamp on a sphere, PASS: the radiometry trial of 2026-11-29).
  double maxRadianceRatio = 0;
  std::size_t pixelsDiffering = 0;      // digital numbers (bitsPerPixel) differ
  std::size_t radianceOutliers = 0;     // pixels whose radiance difference exceeds the tolerance
  std::size_t objectIdMismatches = 0;   // pixel-centre rays hit different objects (or one misses)
  // Of those: pixels away from any edge (no other object, nor background, among the 8 neighbours
  // in the reference). At an edge pixel a ray within rounding distance of a silhouette or a
  // surface's border may go either way (a centre exactly on a straight border of a centred
  // specimen is common); away from edges nothing explains a difference.
  std::size_t radianceOutliersOffEdge = 0;
  std::size_t objectIdMismatchesOffEdge = 0;
  // Pixel-centre rays at an edge pixel that hit different objects at the same point (|ΔP| within
  // the P bound): a ray through an edge two objects share, where either is the nearest hit. Not
  // among the mismatches above nor the wrong hits below; bit-identical renders have none
  // (identical_results.h).
  std::size_t objectTies = 0;
  // Ground truth of the pixel-centre ray, over pixels where both hit the same object.
  double maxUvDiff = 0;                 // max(|Δu|, |Δv|), u and v taken modulo 1 (periodic seams)
  double maxPositionDiff_m = 0;
  double maxDepthDiff_m = 0;
  double maxNormalDiff = 0;             // |ΔN| of the unit normals
  double maxGeometryRatio = 0;          // worst |ΔP| or |Δuv| over its per-pixel bound (≤ 1: fine)
  std::size_t geometryOutliers = 0;     // pixels whose P or uv difference exceeds its bound
  // Wrong nearest hits of the pixel-centre ray, by kind, named so that a wrong root shows as one
  // (they are also among the counts above): the reference hits and the test sees the background
  // (miss) or the reverse (extra hit); both hit, different objects (other object); both hit the
  // same object with |ΔP| over its bound, the test's point farther or nearer along the ray.
  std::size_t wrongMiss = 0, wrongExtraHit = 0, wrongOtherObject = 0, wrongFartherRoot = 0, wrongNearerRoot = 0;
  std::size_t wrongNearestHits() const {
    return wrongMiss + wrongExtraHit + wrongOtherObject + wrongFartherRoot + wrongNearerRoot;
  }
  // The visibility behind flow.mask and disparity.mask (render/visibility.h), where compareVisibility
  // measured it: the reference's pixel-centre hits traced towards `visibilityCamera` by the GPU's
  // query and by the CPU reference; the answers that differ. The query runs in fp64 (df64 without
  // it) whatever the render's precision, so none may differ.
  std::string visibilityCamera;
  std::size_t visibilityPoints = 0, visibilityMismatches = 0;
};

// Tolerances of one precision (values and derivations in compare.cpp, summarized in docs/precision.md).
// fp64 has absolute bounds. fp32 and df64 bound each pixel by the conditioning of its pixel-centre
// hit (ε = the variant's unit roundoff: 2^-24, 2^-44):
//   P:        k ε D / c
//   uv:       k ε (max(1, g |P − O|) + g D / c)
//   radiance: r0 + T · (uv bound)
// with D = |P − C| + |C − O| (camera C, object origin O; the GPU works camera-relative), c = max(cos θ,
// floor) (θ: incidence; floor √ε on curved shapes, ε on flat ones), g = |∂uv/∂P| measured with two
// extra reference rays,
// T = the largest slope of the object's texture times its shading (radiance per unit uv).
struct Tolerances {
  double radiance;     // |Δ radiance| as a fraction of full scale (r0 above)
  double position_m;   // absolute part of the P bound (m)
  double uv;           // absolute part of the uv bound
  double epsilon;      // unit roundoff of the GPU arithmetic (0: absolute bounds only)
  double k;            // number of roundoff steps allowed in the conditioned bound
  // Pixels away from edges allowed over a bound or with a different object, as a fraction of all
  // pixels (fp32: shadow edges, box edges, uv seams); edge pixels are explained (see
  // CameraDifference). 0: no outlier anywhere, edge or not.
  double outlierFraction;
  // --tolerance-scale (scaledTolerances): 1 for the derived bounds. The fields above carry it; this
  // is for the terms counted in fixed roundings rather than k (the lights' inputs,
  // render/shading_tolerance.h).
  double scale = 1;
};

Tolerances tolerancesFor(Precision gpuPrecision);

// The reference's |cos θ| of a ray at its hit as the bounds use it: floored at √ε on curved shapes
// (the tangent saturation, derived at tolerancesFor) and at ε on flat ones.
double conditionedCosine(const Tolerances& tolerances, double cosTheta, bool curved);

// The bound on |ΔP| (m) between the reference's hit of a ray and the GPU's (the derivation at
// tolerancesFor): with epsilon 0 the absolute tolerance.position_m; else k ε D / cos θ, cos θ
// conditioned as above; D the distance of the hit from the ray's origin plus that origin's
// distances to the camera centre and the camera centre's to the object's origin.
double positionBound(const Tolerances& tolerances, double cosTheta, double D_m, bool curved);

// reference and test must come from the same PreparedScene and RenderOptions.
std::vector<CameraDifference> compareResults(const PreparedScene& scene, const RenderResult& reference,
                                             const RenderResult& test, const Tolerances& tolerances);

// Measures `d`'s visibility check for camera `camera` of `reference` (a render of `scene`, with
// geometry): every pixel-centre hit traced towards the camera whose masks ask for it (a stereo rig's
// other camera for disparity.mask, else the camera itself, as flow.mask does) by `tracer` (the GPU's
// query, job/render_job.h gpuVisibilityTracer) and by the CPU reference, in double. Nothing is done
// without a tracer (the CPU reference would be compared with itself).
void compareVisibility(const PreparedScene& scene, const RenderResult& reference, std::size_t camera,
                       const VisibilityTracer& tracer, CameraDifference& d);

// Off-edge outliers allowed in an image of `pixels` (0 where outlierFraction is 0).
double allowedOutliers(const Tolerances& t, std::size_t pixels);
bool withinTolerance(const CameraDifference& d, const Tolerances& t);

// The statistic of `d` that judges a layer the GPU returns (by its slot in the layer schema,
// model/layers.h): the largest difference, or for the object mask the pixels that differ; nothing
// for the layers derived on the host (judged through the traced ones).
std::optional<double> layerDifference(const CameraDifference& d, Layer layer);

// The tolerances multiplied by `factor` in (0, 1] (`compare --tolerance-scale`): the radiance and
// absolute bounds, k (so the conditioned bounds) and the outlier fraction. Stricter only: the
// documented tolerances are derived bounds, and loosening them would hide bugs.
Tolerances scaledTolerances(const Tolerances& t, double factor);

// One line naming each measure over its tolerance, with the measured value and the allowed one,
// e.g. "radiance: 12 px over 1e-3 of full scale off edges (max 2.3e-3; allowed 0 px)". Empty when
// the camera passes.
std::string describeExcess(const CameraDifference& d, const Tolerances& t);

}  // namespace dicsynth
