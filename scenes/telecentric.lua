-- A telecentric lens (Camera.Orthographic, magnification 0.5): two speckled plates of the same size,
-- one at 0.1 m and one at 0.3 m in front of the camera's plane, appear at the same size in the
-- image (0.5 x 6 mm / 10 µm = 300 px wide), and a sphere
-- shows its outline as a circle of radius m r / pixel size whatever its depth. Brown distortion on
-- the metric normalized coordinates (k1 in m⁻²: -200 m⁻² displaces the image corner, 8 mm off
-- the axis, by about 1.3 %). Camera.Orthographic: README "Cameras".
camera = Camera.Orthographic { resolution = {640, 480}; pixelSize = {1e-5, 1e-5}; magnification = 0.5;
  bitsPerPixel = 10; position = {0, 0, -0.05};
  distortion = Distortion.Brown { radial = {-200}; tangential = {0.01, -0.02} } }
near = Object.Simple {
  shape = Shape.Rectangle { size = {0.006, 0.006}; location = {-0.0035, 0, 0.05} };
  transform = rotate_x(degrees(20));
  shader = Shader.Constant { color = 0.9 };
  texture = Texture.File { fileName = "speckle.tif" } }
far = Object.Simple {
  shape = Shape.Rectangle { size = {0.006, 0.006}; location = {0.0035, 0, 0.25} };
  shader = Shader.Constant { color = 0.7 };
  texture = Texture.File { fileName = "speckle.tif" } }
ball = Object.Simple {
  shape = Shape.Sphere { radius = 0.0015; location = {0, 0.003, 0.15} };
  shader = Shader.Lambert { color = 0.8 } }
lamp = Light.Point { position = {0, -0.05, -0.05}; intensity = 0.1 }
