-- A DIC-Challenge-like stereo experiment: the speckled flat plate of stereo_plate.lua (10 cm x
-- 7.5 cm) seen by the same symmetric stereo rig (two 1600 x 1200 cameras, 16 mm lenses, Brown
-- distortion, 12 cm baseline, 50 cm away), moved in frame 1 by an out-of-plane sinusoid whose period
-- grows along x, from 5 mm at the left edge to 25 mm at the right: a test of a stereo-DIC code's
-- spatial resolution of shape and out-of-plane displacement. Nurbs.deform fits the deformed surface
-- to `tolerance` with the plate's own (u, v), so the texture moves with the material; disp,
-- flow and disparity in frame 1's files are the field as rendered, fieldError the rendered minus
-- the requested displacement (at most the fit error printed on stderr).
-- Parameters:
--   -D amplitude=<m>    amplitude of the out-of-plane wave (default 5e-5 m)
--   -D tolerance=<m>    fit tolerance (default 1e-9 m)
-- Example: dicsynth render scenes/stereo_sinusoid.lua --frames 0:1
amplitude = amplitude or 5e-5
tolerance = tolerance or 1e-9
local function camera(k1)
  return Camera.Pinhole { resolution = {1600, 1200}; focalLength = 0.016; pixelSize = {3.45e-6, 3.45e-6};
    bitsPerPixel = 10; distortion = Distortion.Brown { radial = {k1, 0.08, 0}; tangential = {2e-4, -1e-4} } }
end
rig = Rig.Stereo { left = camera(-0.09); right = camera(-0.11); baseline = 0.12; target = {0, 0, 0.5} }
local reference = Nurbs.plate { size = {0.1, 0.075}; spans = {8, 4}; location = {0, 0, 0.5} }
-- Phase of a chirp: the local period 0.005 + 0.2 (x + 0.05) m grows linearly from 5 to 25 mm,
-- and the phase is the integral of 2 pi / period along x.
local function phase(x)
  return 2 * math.pi / 0.2 * math.log((0.005 + 0.2 * (x + 0.05)) / 0.005)
end
local function wave(x, y, z)
  return 0, 0, amplitude * math.sin(phase(x))
end
plate = Object.Simple {
  shape = frame >= 1 and Nurbs.deform { surface = reference; displacement = wave; tolerance = tolerance } or reference;
  shader = Shader.Constant { color = 0.9 };
  texture = Texture.File { fileName = "speckle.tif" } }
