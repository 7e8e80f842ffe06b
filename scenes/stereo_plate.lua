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
-- Example: dicsynth render scenes/stereo_plate.lua --frames 0:1
strain = strain or 0.002
curvature = curvature or 1
local e = frame >= 1 and strain or 0
local k = frame >= 1 and curvature or 0
local function camera(k1)
  return Camera.Pinhole { resolution = {1600, 1200}; focalLength = 0.016; pixelSize = {3.45e-6, 3.45e-6};
    bitsPerPixel = 10; distortion = Distortion.Brown { radial = {k1, 0.08, 0}; tangential = {2e-4, -1e-4} } }
end
rig = Rig.Stereo { left = camera(-0.09); right = camera(-0.11); baseline = 0.12; target = {0, 0, 0.5} }
plate = Object.Simple {
  shape = Nurbs.plate { size = {0.1, 0.075}; strain = {e, -0.3 * e}; curvature = k; spans = {8, 4};
    location = {0, 0, 0.5} };
  shader = Shader.Constant { color = 0.9 };
  texture = Texture.File { fileName = "speckle.tif" } }
