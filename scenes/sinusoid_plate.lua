-- A DIC-Challenge-like virtual experiment: a speckled flat plate (10 cm x 5 cm, Nurbs.plate) 40 cm
-- in front of a 1600 x 1200 camera (16 mm lens, 3.45 um pixels), moved in frame 1 by a sinusoidal
-- displacement across the plate (along y) whose period grows along x, from 4 mm at the left edge to
-- 10 mm at the right: a field that tests a DIC code's spatial resolution. Nurbs.deform fits the
-- deformed surface to `tolerance` with the plate's own (u, v), so the texture moves with the
-- material and disp/flow in frame 1's files are the field as rendered; stderr reports the fit error.
-- Parameters:
--   -D amplitude=<m>    amplitude of the wave (default 2e-5 m)
--   -D tolerance=<m>    fit tolerance (default 1e-9 m)
-- Example: dicsynth render scenes/sinusoid_plate.lua --frames 0:1
amplitude = amplitude or 2e-5
tolerance = tolerance or 1e-9
camera = Camera.Pinhole { resolution = {1600, 1200}; focalLength = 0.016; pixelSize = {3.45e-6, 3.45e-6};
  bitsPerPixel = 10 }
local reference = Nurbs.plate { size = {0.1, 0.05}; spans = {8, 4}; location = {0, 0, 0.4} }
local function wave(x, y, z)
  local period = 0.004 + 0.06 * (x + 0.05)  -- x in the plate's own frame: -0.05 .. 0.05 m
  return 0, amplitude * math.sin(2 * math.pi * x / period), 0
end
plate = Object.Simple {
  shape = frame >= 1 and Nurbs.deform { surface = reference; displacement = wave; tolerance = tolerance } or reference;
  shader = Shader.Constant { color = 0.9 };
  texture = Texture.File { fileName = "speckle.tif" } }
