-- The pipeline benchmark's scene (bench/bench_pipeline_cold.sh): a textured floor and `spheres`
-- Lambert spheres on a grid in front of a 640 × 480 camera, lit by `lights` point lights whose
-- shadows fall on the floor. The object count (spheres + 1) decides whether the GPU pipeline is
-- specialized to an exact count (shaders/shared/bindings.h, DS_MAX_UNROLLED_OBJECTS). Kept out of
-- scenes/ (the CPU-vs-GPU test renders every scene there).
spheres = spheres or 5
lights = lights or 2
camera = Camera.Pinhole { resolution = {640, 480}; focalLength = 0.012; pixelSize = {1.5e-5, 1.5e-5};
  bitsPerPixel = 12; distortion = Distortion.Brown { radial = {-0.1, 0.05, 0} } }
floor = Object.Simple { shape = Shape.Rectangle { size = {2, 2}; location = {0, 0, 1.2} };
  shader = Shader.Lambert { color = 0.8 }; texture = Texture.File { fileName = "../scenes/speckle.tif" } }
for i = 0, spheres - 1 do
  _G["ball" .. i] = Object.Simple {
    shape = Shape.Sphere { radius = 0.03; location = {-0.35 + 0.1 * (i % 8), -0.25 + 0.1 * (i // 8), 1.0 + 0.01 * (i % 3)} };
    shader = Shader.Lambert { color = 0.6 } }
end
for l = 0, lights - 1 do
  _G["light" .. l] = Light.Point { position = {-0.4 + 0.16 * l, -0.5, 0.3}; intensity = 0.3 / lights }
end
