-- A stereo pair of a deformable specimen before and after an imposed strain: the speckled NURBS
-- plate of nurbs_plate.lua (10 cm x 7.5 cm, Nurbs.plate) 50 cm in front of a symmetric stereo rig
-- (Rig.Stereo: two 1600 x 1200 cameras with 16 mm lenses and Brown distortion, 12 cm apart,
-- optical axes crossing at the plate's centre, i.e. about 13.7 degrees of vergence). Frame 0 is the
-- undeformed reference, frame 1 the plate under uniaxial strain along x (Poisson ratio 0.3) and
-- slightly bent: render --frames 0:1. The ground truth of each image: disp and flow (from frame 0),
-- disparity to the other camera of the rig, and the rig's calibration files.
-- Parameters:
--   -D strain=<e>       engineering strain of frame 1 along x (default 0.002)
--   -D curvature=<1/m>  bending of frame 1 about the vertical axis (default 1)
--   -D calibration=true instead of the plate, a 10 x 7 checkerboard (8 mm squares, 9 x 6 inner
--                       corners) in 15 poses, frames 0..14, 45 to 60 cm away, tilted up to 30
--                       degrees: the calibration set of this very rig (scenes/stereo_calibration.lua
--                       has a rig of its own; scenes/stereo_sinusoid.lua has this one)
-- Example: dicsynth render scenes/stereo_plate.lua --frames 0:1
--          dicsynth render scenes/stereo_plate.lua -D calibration=true --frames 0:14 --layers image -o calib
strain = strain or 0.002
curvature = curvature or 1
calibration = calibration or false
-- Any value but false and nil is true in Lua: -D calibration=0 (or =no) rendered the board.
if type(calibration) ~= "boolean" then
  error("-D calibration=" .. tostring(calibration) .. ": give true or false")
end
local e = frame >= 1 and strain or 0
local k = frame >= 1 and curvature or 0
local function camera(k1)
  return Camera.Pinhole { resolution = {1600, 1200}; focalLength = 0.016; pixelSize = {3.45e-6, 3.45e-6};
    bitsPerPixel = 10; distortion = Distortion.Brown { radial = {k1, 0.08, 0}; tangential = {2e-4, -1e-4} } }
end
rig = Rig.Stereo { left = camera(-0.09); right = camera(-0.11); baseline = 0.12; target = {0, 0, 0.5} }
if calibration then
  local board_spec = { squares = {10, 7}; squareSize = 0.008; border = 0.008 }
  local poses = Target.poses { target = Target.Checkerboard(board_spec); cameras = {rig.left, rig.right};
    count = 15; seed = 1; distance = {0.45, 0.6}; tilt = degrees(30); margin = 20 }
  board_spec.transform = poses[frame + 1]  -- an error for a frame outside 0..14
  board = Target.Checkerboard(board_spec)
else
  plate = Object.Simple {
    shape = Nurbs.plate { size = {0.1, 0.075}; strain = {e, -0.3 * e}; curvature = k; spans = {8, 4};
      location = {0, 0, 0.5} };
    shader = Shader.Constant { color = 0.9 };
    texture = Texture.File { fileName = "speckle.tif" } }
end
