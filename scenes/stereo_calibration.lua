-- A stereo calibration set: a 10 x 7 checkerboard (12 mm squares, 9 x 6 inner corners) in 15 poses,
-- seen by two 1600 x 1200 cameras (12 mm lenses, 4.4 um pixels, 8 bits) 15 cm apart, converging on
-- a point 50 cm ahead, each with its own Brown distortion and principal point.
-- The poses come from Target.poses: deterministic for the seed, every inner corner at least 20 px
-- inside both images, the board's centre 35 to 50 cm away, tilted up to 35 degrees.
-- Render all 15 frames (30 images, and per image the ground truth of every corner:
-- out/<camera>_<frame>.features.csv/.json):
--   build/dicsynth render scenes/stereo_calibration.lua --frames 0:14 -o out
-- (files out/rig.left_0000.tif ... out/rig.right_0014.tif)
-- Calibrate with OpenCV: cv::findChessboardCornersSB(image, {9, 6}, corners) and object points
-- (col * 0.012, row * 0.012, 0), as tests/io/test_opencv_calibration.cpp does; the accuracy it reaches
-- is in docs/calibration.md.
-- The cameras are the rig's: rig.left and rig.right (Rig.Stereo), files named accordingly; the
-- rig's calibration files (out/rig.yml, out/rig.dice.xml) state the true intrinsics, distortion
-- and the stereo R, T that cv::stereoCalibrate should recover.
local left = Camera.Pinhole { resolution = {1600, 1200}; principalPoint = {805.5, 596.0}; focalLength = 0.012;
  pixelSize = {4.4e-6, 4.4e-6}; bitsPerPixel = 8;
  distortion = Distortion.Brown { radial = {-0.12, 0.08, 0}; tangential = {3e-4, -2e-4} } }
local right = Camera.Pinhole { resolution = {1600, 1200}; principalPoint = {794.0, 603.5}; focalLength = 0.012;
  pixelSize = {4.4e-6, 4.4e-6}; bitsPerPixel = 8;
  distortion = Distortion.Brown { radial = {-0.09, 0.05, 0}; tangential = {-2e-4, 1e-4} } }
rig = Rig.Stereo { left = left; right = right; baseline = 0.15; target = {0, 0, 0.5} }

local board_spec = { squares = {10, 7}; squareSize = 0.012; border = 0.012 }
local poses = Target.poses { target = Target.Checkerboard(board_spec); cameras = {rig.left, rig.right};
  count = 15; seed = 1; distance = {0.35, 0.5}; tilt = degrees(35); margin = 20 }
board_spec.transform = poses[frame + 1]  -- an error for a frame outside 0..14
board = Target.Checkerboard(board_spec)
