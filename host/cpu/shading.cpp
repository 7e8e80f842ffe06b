#include "cpu/shading.h"

#include "cpu/trace.h"

namespace dicsynth::cpu {

double spotFactor(const PreparedLight& light, dvec3 point) {
  if (light.kind != LightKind::Spot) return 1;
  const dvec3 fromLight = point - light.position_m;
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
    const dvec3 toLight = light.position_m - hit.position;
    const double r2 = glm::dot(toLight, toLight);
    const double r = std::sqrt(r2);
    const double cosTheta = glm::dot(hit.normal, toLight) / r;
    if (!(cosTheta > 0)) continue;
    const double s = spotFactor(light, hit.position);
    if (!(s > 0) || occluded(scene, hit, light.position_m)) continue;
    const double e = light.intensity * s * cosTheta / r2;
    diffuse += e;
    if (model.specular) specular += specularBrdf(obj, hit.normal, toLight / r, toViewer) * e;
  }
  return rho * diffuse / kPi + specular + rho * ambient;
}

}  // namespace dicsynth::cpu
