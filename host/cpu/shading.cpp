#include "cpu/shading.h"

#include "cpu/trace.h"

namespace dicsynth::cpu {

double specularBrdf(const PreparedObject& obj, dvec3 n, dvec3 wi, dvec3 wo) {
  switch (obj.shader) {
    case ShaderKind::Constant:
    case ShaderKind::Lambert: return 0;
    case ShaderKind::Phong: {
      const dvec3 mirror = 2 * glm::dot(n, wi) * n - wi;  // ωi reflected about the normal
      return phongLobe(obj.specular, obj.shininess, glm::dot(mirror, wo));
    }
    case ShaderKind::BlinnPhong:
      return blinnPhongLobe(obj.specular, obj.shininess, glm::dot(n, glm::normalize(wi + wo)));
    case ShaderKind::Ggx: {
      const double cosI = glm::dot(n, wi), cosO = glm::dot(n, wo);
      if (!(cosI > 0) || !(cosO > 0)) return 0;
      const dvec3 half = glm::normalize(wi + wo);
      const dvec3 nxh = glm::cross(n, half);
      return ggxD(obj.roughness, glm::dot(n, half), glm::dot(nxh, nxh)) * schlickFresnel(obj.f0, glm::dot(wo, half)) *
             ggxVisibility(obj.roughness, cosI, cosO);
    }
  }
  return 0;
}

double spotFactor(const PreparedLight& light, dvec3 point) {
  if (light.kind != LightKind::Spot) return 1;
  const dvec3 fromLight = point - light.position_m;
  const double cosPhi = glm::dot(light.direction, fromLight) / std::sqrt(glm::dot(fromLight, fromLight));
  const double t = std::clamp((cosPhi - light.cosOuter) / (light.cosInner - light.cosOuter), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

double shadeSurface(const PreparedScene& scene, const SurfaceHit& hit, double reflectance) {
  const PreparedObject& obj = scene.objects[std::size_t(hit.object)];
  if (obj.shader == ShaderKind::Constant) return reflectance;
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
    if (obj.shader != ShaderKind::Lambert) specular += specularBrdf(obj, hit.normal, toLight / r, toViewer) * e;
  }
  return reflectance * diffuse / kPi + specular + reflectance * ambient;
}

}  // namespace dicsynth::cpu
