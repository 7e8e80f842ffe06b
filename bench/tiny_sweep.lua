-- The memory benchmark's scene (bench/bench_sweep.sh): a 32×24 camera and a plate whose offset is
-- the sweep parameter, no texture, so that any memory a point leaves behind is not hidden under a
-- large texture. Kept out of scenes/ (the CPU-vs-GPU test renders every scene there).
shift = shift or 0
cam = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }
plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {shift, 0, 0.5} };
  shader = Shader.Constant { color = 0.5 } }
sweep = { shift = linspace(0, 0.01, 10) }
