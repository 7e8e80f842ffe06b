-- A speckled rectangle seen through a realistic machine-vision sensor (docs/sensor.md): shot and
-- read noise of an EMVA 1288-style preset, a slight lens blur, cos⁴ vignetting, one dust blob and a
-- few defective pixels (with their own seed: a sensor's defects stay when --seed changes). The
-- sensor acts after the renderer, so the rendered radiance is that of rectangle.lua at a smaller
-- size; the noise changes with --seed and with the frame.
-- Parameter: -D exposure=<number> scales the signal (default 0.8: the brightest speckle at ~72 %
-- of the full well).
exposure = exposure or 0.8
camera = Camera.Pinhole { resolution = {320, 240}; focalLength = 0.0064; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 12; exposure = exposure;
  sensor = Sensor.Emva { preset = "machine-vision-cmos" };
  postProcessing = {
    Blur.Gaussian { sigma_px = 0.6 },
    Vignetting.Cos4 {},
    Dust { center_px = {240, 60}; radius_px = 25; opacity = 0.35 },
    DefectivePixels { hot = 2e-4; dead = {{100, 100}}; stuck = {{200, 150}}; seed = 1 },
  }; };
specimen = Object.Simple {
  shape = Shape.Rectangle { size = {0.1, 0.075}; location = {0, 0, 0.4}; };
  shader = Shader.Constant { color = 0.9; };
  texture = Texture.File { fileName = "speckle.tif"; }; };
