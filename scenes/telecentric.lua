-- A telecentric lens (Camera.Orthographic, magnification 0.5): a speckled plate 6 mm wide at 0.1 m
-- in front of the camera's plane appears 0.5 x 6 mm / 10 µm = 300 px wide, and a checkerboard of
-- 0.8 mm squares at 0.3 m shows squares of 40 px (its feature files give the corners through the
-- telecentric model); a pinhole would shrink the far one threefold. A sphere
-- shows its outline as a circle of radius m r / pixel size whatever its depth. Brown distortion on
-- the metric normalized coordinates (k1 in m⁻²: -200 m⁻² displaces the image corner, 8 mm off
-- the axis, by about 1.3 %). Camera.Orthographic: docs/cameras.md.
camera = Camera.Orthographic { resolution = {640, 480}; pixelSize = {1e-5, 1e-5}; magnification = 0.5;
  bitsPerPixel = 10; position = {0, 0, -0.05};
  distortion = Distortion.Brown { radial = {-200}; tangential = {0.01, -0.02} } }
near = Object.Simple {
  shape = Shape.Rectangle { size = {0.006, 0.006}; location = {-0.0035, 0, 0.05} };
  transform = rotate_x(degrees(20));
  shader = Shader.Constant { color = 0.9 };
  texture = Texture.File { fileName = "speckle.tif" } }
far = Target.Checkerboard { squares = {6, 6}; squareSize = 0.0008; location = {0.0019, -0.0016, 0.25} }
ball = Object.Simple {
  shape = Shape.Sphere { radius = 0.0015; location = {0, 0.003, 0.15} };
  shader = Shader.Lambert { color = 0.8 } }
lamp = Light.Point { position = {0, -0.05, -0.05}; intensity = 0.1 }
