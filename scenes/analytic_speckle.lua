-- Texture.Speckle: an analytic Boolean-model speckle (dark disks, radius 3 px at this distance,
-- half the area covered) defined directly in (u, v) of a 10 cm x 7.5 cm rectangle seen by an
-- 800 x 600 camera 40 cm away (125 um per px): no image, no interpolation, every sample decided
-- exactly. radius is in u units: 0.375 mm / 0.1 m; aspect = 0.075 / 0.1 makes the disks round.
-- Parameter: -D texture="cubic" or "quintic" shows instead scenes/speckle.tif with that Texture.File
-- interpolation (bench/RESULTS.md compares their cost); -D shift=<metres> translates along x.
shift = shift or 0
texture = texture or "speckle"
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.016; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 8; };
local pattern
if texture == "speckle" then
  pattern = Texture.Speckle { radius = 0.00375; density = 0.5; aspect = 0.75; seed = 7; dark = 0.1; light = 0.9; }
else
  pattern = Texture.File { fileName = "speckle.tif"; interpolation = texture; }
end
texture = nil  -- only objects are rendered; keep the globals clean
specimen = Object.Simple {
  shape = Shape.Rectangle { size = {0.1, 0.075}; location = {shift, 0, 0.4}; };
  shader = Shader.Constant { color = 0.9; };
  texture = pattern; };
