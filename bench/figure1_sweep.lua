-- The sweep benchmark's scene (bench/bench_sweep.sh): Figure 1 (scenes/figure1.lua) with the
-- sphere's turn as the sweep parameter `angle` (degrees, default 35: then it is Figure 1 exactly).
-- Kept out of scenes/ so that the CPU-vs-GPU test does not render it.
angle = angle or 35
camera1 = Camera.Pinhole { resolution = {1600, 1200}; principalPoint = {800, 600}; focalLength = 0.012;
  pixelSize = {4.4e-6, 4.4e-6}; fillFactor = 0.9; bitsPerPixel = 10;
  distortion = Distortion.Brown { radial = {-0.13, -0.39, 1.20}; tangential = {1.1e-6, -1.2e-6}; }; };
object = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, 0.5}; };
  shader = Shader.Constant { color = {.2, .8, 1}; }; texture = Texture.File { fileName = "../scenes/speckle.tif"; };
  transform = rotate_y(degrees(angle)); };
sweep = { angle = linspace(30, 40, 50) }
