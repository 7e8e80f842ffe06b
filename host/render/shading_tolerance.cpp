#include "render/shading_tolerance.h"

#include <algorithm>
#include <cmath>

namespace dicsynth {

// The texture's largest |value| (its home bounds it: a B-spline by its largest coefficient, the
// others by their constants), floored at 1.
double reflectanceMax(const PreparedObject& o) {
  return o.albedo * std::max(1.0, textures::maxValue(o.texture));
}

double lightingRadianceBound(const PreparedScene& scene, const PreparedObject& o, const ShadingErrorInputs& in) {
  const reflectance::KindInfo& model = reflectance::kindInfo(o.shader);
  if (!model.lit) return 0;
  // The lobe's largest f_spec · cosθi and its relative slope (the model's home derives them).
  const reflectance::LobeBound lobe = model.specular ? reflectance::lobeBound(o.shader, in.cosView) : reflectance::LobeBound{};
  const double own = in.k * in.epsilon;
  const double normalError = own + in.normalSlope * in.positionBound_m;
  const double diffuseMax = in.reflectanceMax / kPi;
  const double pointToCamera = glm::length(in.position - in.cameraCentre);
  double bound = 0;
  for (const PreparedLight& l : scene.lights) {
    if (l.kind == LightKind::Ambient) continue;
    const dvec3 toLight = l.position_m - in.position;
    const double r2 = glm::dot(toLight, toLight), r = std::sqrt(r2);
    // δx of the header: the vector to the light as the float shading has it. The 2 roundings are
    // scaled by --tolerance-scale as k is (δP is already): unscaled, a strict check of a lit scene
    // kept this term whole and passed differences 1e5 times its printed tolerance (the compare
    // audit of 2026-11-28).
    const double lightToCamera = glm::length(l.position_m - in.cameraCentre);
    const double inputError = in.positionBound_m + 2 * in.scale * in.epsilon * (pointToCamera + lightToCamera + r);
    const double directionError = own + inputError / r;
    double perLight = diffuseMax * (3 * inputError / r + in.normalSlope * in.positionBound_m);
    if (model.specular) perLight += lobe.maxValue * lobe.slope * (4 * normalError + 3 * directionError);
    if (l.kind == LightKind::Spot)
      perLight += (diffuseMax + lobe.maxValue) * 1.5 * directionError / (l.cosInner - l.cosOuter);
    bound += l.intensity / r2 * perLight;
  }
  return bound;
}

}  // namespace dicsynth
