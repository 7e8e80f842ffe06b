#include "cpu/shading.h"

#include "cpu/trace.h"

namespace dicsynth::cpu {

double spotFactor(const PreparedLight& light, dvec3 fromLight) {
  if (light.kind != LightKind::Spot) return 1;
  const double cosPhi = glm::dot(light.direction, fromLight) / std::sqrt(glm::dot(fromLight, fromLight));
  const double t = std::clamp((cosPhi - light.cosOuter) / (light.cosInner - light.cosOuter), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

double shadeSurface(const PreparedScene& scene, const SurfaceHit& hit, double rho) {
  const PreparedObject& obj = scene.objects[std::size_t(hit.object)];
  const reflectance::KindInfo& model = reflectance::kindInfo(obj.shader);
  if (!model.lit) return rho;
  const dvec3 toViewer = -glm::normalize(hit.rayDirection);
  // Irradiance-like sums: diffuse Σ I s cosθ / r², specular Σ f_spec I s cosθ / r², ambient Σ L_a.
  double diffuse = 0, specular = 0, ambient = 0;
  for (const PreparedLight& light : scene.lights) {
    if (light.kind == LightKind::Ambient) {
      ambient += light.intensity;
      continue;
    }
    // Formed relative to the ray's origin, (Q − o) − t d, as the GPU shades in camera-relative
    // coordinates: Q − hit.position would carry the world point's rounding, ~1e-16 of its distance
    // from the world origin, which over the lamp's distance r put a sphere 5,000 km out (r = 0.25 m)
    // 2e-9 off in radiance, over fp64's 1e-9 (precision.md, far from the world origin).
    const dvec3 toLight = (light.position_m - hit.rayOrigin) - hit.t * hit.rayDirection;
    const double r2 = glm::dot(toLight, toLight);
    const double r = std::sqrt(r2);
    const double cosTheta = glm::dot(hit.normal, toLight) / r;
    if (!(cosTheta > 0)) continue;
    const double s = spotFactor(light, -toLight);
    if (!(s > 0) || occluded(scene, hit, light.position_m)) continue;
    const double e = light.intensity * s * cosTheta / r2;
    diffuse += e;
    if (model.specular) specular += specularBrdf(obj, hit.normal, toLight / r, toViewer) * e;
  }
  return rho * diffuse / kPi + specular + rho * ambient;
}

}  // namespace dicsynth::cpu
