-- Texture.File with the quintic B-spline interpolation (host/texture/bspline.h): the speckle image
-- of scenes/rectangle.lua on a disk-shaped view of a sphere, so the texture is sampled at every
-- sub-texel phase and scale; compared CPU vs GPU like every scene.
camera = Camera.Pinhole { resolution = {400, 300}; focalLength = 0.016; pixelSize = {1e-5, 1e-5}; };
ball = Object.Simple {
  shape = Shape.Sphere { radius = 0.05; location = {0, 0, 0.4}; };
  shader = Shader.Constant { color = 0.9; };
  texture = Texture.File { fileName = "speckle.tif"; interpolation = "quintic"; }; };
