-- 360° DIC of a tube: an open tube (radius 2 cm, 8 cm long, axis along y) with an analytic speckle,
-- seen by four 800 x 600 cameras set 90° apart around it, 30 cm from its axis (16 mm lenses, Brown
-- distortion: 0.09 mm per pixel on the tube). Frame k expands the tube radially by k x strain (the
-- radius 2 cm x (1 + k x strain), the height unchanged): a uniform hoop strain, whose exact
-- displacement strain x k x (x, 0, z) of each material point every camera's .exr holds as disp,
-- with flow and flow.mask. Each camera has its own calibration file (cam0.yml ... cam3.yml), all
-- in the one world frame of the scene. The tube's seam (u = 1 meets u = 0, facing +z) is in the view
-- of cam2 (at +z): wrap = "repeatU" continues the speckle across it, as on a real tube.
-- Parameters:
--   -D strain=<1>     hoop strain per frame (default 0.001)
--   -D cameras=<n>    number of cameras around the tube, 2 to 12 (default 4)
-- Example: dicsynth render scenes/tube_360.lua --frames 0:1 -o tube
strain = strain or 0.001
cameras = cameras or 4
assert(cameras >= 2 and cameras <= 12 and cameras == math.floor(cameras), "cameras must be an integer in 2..12")
for k = 0, cameras - 1 do
  local angle = 2 * math.pi * k / cameras  -- cam0 at -z (in front of the tube), then clockwise seen from above
  _G["cam" .. k] = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.016; pixelSize = {5e-6, 5e-6};
    bitsPerPixel = 12; distortion = Distortion.Brown { radial = {-0.05, 0.01} };
    position = {0.3 * math.sin(angle), 0, -0.3 * math.cos(angle)}; lookAt = {0, 0, 0} }
end
tube = Object.Simple {
  shape = Shape.Cylinder { radius = 0.02 * (1 + frame * strain); height = 0.08; capped = false };
  shader = Shader.Constant { color = 0.9 };
  -- u runs once around (12.6 cm), v along the 8 cm: aspect 0.08 / 0.126 keeps the disks round. A
  -- radius of 0.0025 u is 0.31 mm, 3.5 px across a disk; wrap rounds it to 1/(2 x 200) = 0.0025.
  texture = Texture.Speckle { radius = 0.0025; aspect = 0.08 / (2 * math.pi * 0.02); seed = 11; wrap = "repeatU" } }
