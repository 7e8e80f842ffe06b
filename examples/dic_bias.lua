-- The scene of examples/dic_bias.py: a flat plate (10 cm x 7.5 cm) with an analytic speckle
-- (Texture.Speckle: no image interpolation in the rendering, so the bias measured is the DIC's)
-- of disks 1.2 mm across, about 5 px on this 400 x 300 camera 40 cm away (0.25 mm per pixel), moved
-- by frame x step_px pixels along the image x axis in its own plane.
-- Parameters: -D step_px=<px> (default 0.05)
step_px = step_px or 0.05
local metresPerPixel = 0.4 * 10e-6 / 0.016  -- Z * pixelSize / focalLength = 0.25 mm
camera = Camera.Pinhole { resolution = {400, 300}; focalLength = 0.016; pixelSize = {10e-6, 10e-6}; bitsPerPixel = 12 }
specimen = Object.Simple {
  shape = Shape.Rectangle { size = {0.1, 0.075}; location = {frame * step_px * metresPerPixel, 0, 0.4} };
  shader = Shader.Constant { color = 0.9 };
  texture = Texture.Speckle { radius = 0.006; density = 0.5; aspect = 0.75; seed = 3; dark = 0.1; light = 0.9 } }
