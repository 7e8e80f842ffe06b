-- A speckled pipe turning about its own axis: an open Shape.Cylinder (radius 2 cm, 8 cm long)
-- 50 cm from an 800 x 600 camera, tilted 35° so that its inside shows through its top end,
-- under a point light (shading and the pipe's own shadow inside it). Frame k turns the pipe by
-- k x step_deg degrees about its axis: a rigid rotation of a curved surface, whose exact
-- displacement (disp) and image motion (flow, flow.mask for what turns out of view) every frame's
-- .exr holds per reference pixel. Texture.Speckle: disks defined in (u, v), no image interpolation.
-- Parameters:
--   -D step_deg=<deg>   rotation per frame about the pipe's axis in degrees (default 0.2)
--   -D capped=true      close the ends (a solid rod instead of a pipe)
-- Example: dicsynth render scenes/pipe.lua --frames 0:5
step_deg = step_deg or 0.2
capped = capped or false
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.012; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 12; distortion = Distortion.Brown { radial = {-0.05, 0.01}; }; };
pipe = Object.Simple {
  shape = Shape.Cylinder { radius = 0.02; height = 0.08; capped = capped; location = {0, 0, 0.5}; };
  shader = Shader.Lambert { color = 0.85; };
  -- u runs once around the circumference (12.6 cm), v along the 8 cm (aspect 0.64): a radius of
  -- 0.003 in u is 0.38 mm, 1.8 px at this distance (1 px = 0.5 m x 5 µm / 12 mm = 0.21 mm).
  -- The seam (u = 1 meets u = 0) faces away from the camera outside but is in view on the inner
  -- wall through the top end: wrap = "repeatU" continues the disks across it (the radius rounded
  -- to a whole number of cells around: 1/(2 x 167) = 0.002994).
  texture = Texture.Speckle { radius = 0.003; aspect = 0.64; seed = 7; wrap = "repeatU"; };
  transform = rotate_x(degrees(35)) * rotate_y(degrees(frame * step_deg)); };
lamp = Light.Point { position = {0.1, -0.15, 0.0}; intensity = 0.8; };
