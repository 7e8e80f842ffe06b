#pragma once
// What every reflectance model's home shares (host/reflectance/<kind>.h, registry.h): the bound of
// its specular lobe that the comparison uses, and integer powers. The radiance sum over lights
// that all models share is in host/cpu/shading.h (and its GLSL twin shaders/lib/shading.glsl).
namespace dicsynth::reflectance {

// Largest f_spec · cosθi over light directions (per steradian) for a viewer at cosθo = cosView,
// and the largest relative slope of that product per unit change of the lobe's cosines
// (render/shading_tolerance.h turns them into a radiance bound). Zero for models without a lobe.
struct LobeBound {
  double maxValue = 0;
  double slope = 0;
};

}  // namespace dicsynth::reflectance
