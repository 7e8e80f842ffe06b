#include "render/shading_tolerance.h"

#include <algorithm>
#include <cmath>

namespace dicsynth {

// The texture's largest |value| (its home bounds it: a B-spline by its largest coefficient, the
// others by their constants), floored at 1.
double reflectanceMax(const PreparedObject& o) {
  return o.albedo * std::max(1.0, textures::maxValue(o.texture));
}

bool hasSpecularOrSpotTerms(const PreparedScene& scene, const PreparedObject& o) {
  const reflectance::KindInfo& model = reflectance::kindInfo(o.shader);
  if (!model.lit) return false;
  if (model.specular) return true;
  return std::any_of(scene.lights.begin(), scene.lights.end(),
                     [](const PreparedLight& l) { return l.kind == LightKind::Spot; });
}

double specularRadianceBound(const PreparedScene& scene, const PreparedObject& o, const ShadingErrorInputs& in) {
  if (!hasSpecularOrSpotTerms(scene, o)) return 0;
  // The lobe's largest f_spec · cosθi and its relative slope (the model's home derives them).
  const reflectance::LobeBound lobe = reflectance::lobeBound(o.shader, in.cosView);
  const double maxValue = lobe.maxValue, slope = lobe.slope;
  const double own = in.k * in.epsilon;
  const double normalError = own + in.normalSlope * in.positionBound_m;
  const double diffuseMax = in.reflectanceMax / kPi;
  double bound = 0;
  for (const PreparedLight& l : scene.lights) {
    if (l.kind == LightKind::Ambient) continue;
    const dvec3 toLight = l.position_m - in.position;
    const double r2 = glm::dot(toLight, toLight), r = std::sqrt(r2);
    const double directionError = own + in.positionBound_m / r;
    const double cosError = 4 * normalError + 3 * directionError;
    double perLight = maxValue * slope * cosError;
    if (l.kind == LightKind::Spot)
      perLight += (diffuseMax + maxValue) * 1.5 * directionError / (l.cosInner - l.cosOuter);
    bound += l.intensity / r2 * perLight;
  }
  return bound;
}

}  // namespace dicsynth
