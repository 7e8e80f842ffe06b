#pragma once
// PreparedScene → the std430 arrays of shaders/shared/gpu_types.h, in one precision variant.
// Doubles are rounded to the variant's `real` here and nowhere else.
#include <vector>

#include "geometry/prepared_scene.h"
#include "gpu/gpu_layout.h"

namespace dicsynth::gpu {

template <class Layout>
struct PackedScene {
  std::vector<typename Layout::GpuCamera> cameras;
  std::vector<typename Layout::GpuObject> objects;
  std::vector<typename Layout::GpuLight> lights;
  std::vector<typename Layout::GpuTexture> textures;
  std::vector<typename Layout::real> texels;  // all textures' B-spline coefficients, concatenated
};

// Layout traits: which namespace of gpu_layout.h a variant uses.
struct Fp32Layout {
  using real = float;
  using real4 = fp32::real4;
  using GpuCamera = fp32::GpuCamera;
  using GpuObject = fp32::GpuObject;
  using GpuLight = fp32::GpuLight;
  using GpuTexture = fp32::GpuTexture;
  using GpuPixel = fp32::GpuPixel;
  using GpuTileParams = fp32::GpuTileParams;
};
struct Fp64Layout {
  using real = double;
  using real4 = fp64::real4;
  using GpuCamera = fp64::GpuCamera;
  using GpuObject = fp64::GpuObject;
  using GpuLight = fp64::GpuLight;
  using GpuTexture = fp64::GpuTexture;
  using GpuPixel = fp64::GpuPixel;
  using GpuTileParams = fp64::GpuTileParams;
};

template <class Layout>
PackedScene<Layout> packScene(const PreparedScene& scene, int samplesPerPixel);

}  // namespace dicsynth::gpu
