-- The classic DIC sanity test: a rigid-body translation or rotation series of a flat speckled
-- specimen (10 cm x 7.5 cm) facing an 800 x 600 camera 40 cm away (fx = 3200 px, so 1 px in the
-- image is 0.125 mm on the specimen), without distortion, under constant shading. Frame 0 is the
-- reference; every frame's .exr holds the exact displacement (disp) and image motion (flow) of
-- each reference pixel, so a DIC code's error is its result minus flow.
-- Parameters:
--   -D motion="translation"  (default) frame k moves the specimen by k x step_px pixels along
--                            the image x axis, in its own plane
--   -D motion="rotation"     frame k turns it by k x step_deg degrees about the optical axis
--                            through its centre
--   -D step_px=<px>          translation per frame in image pixels (default 0.1)
--   -D step_deg=<deg>        rotation per frame in degrees (default 0.5)
-- Example: dicsynth render scenes/rigid_motion.lua --frames 0:10
--          dicsynth render scenes/rigid_motion.lua --frames 0:10 -D motion=rotation
motion = motion or "translation"
step_px = step_px or 0.1
step_deg = step_deg or 0.5
local metresPerPixel = 0.4 * 5e-6 / 0.016  -- Z * pixelSize / focalLength
local shift, turn = 0, 0
if motion == "translation" then
  shift = frame * step_px * metresPerPixel
elseif motion == "rotation" then
  turn = frame * step_deg
else
  error("motion must be \"translation\" or \"rotation\", not \"" .. tostring(motion) .. "\"")
end
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.016; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 8; };
specimen = Object.Simple {
  shape = Shape.Rectangle { size = {0.1, 0.075}; location = {shift, 0, 0.4}; };
  shader = Shader.Constant { color = 0.9; };
  texture = Texture.File { fileName = "speckle.tif"; };
  transform = rotate_z(degrees(turn)); };
