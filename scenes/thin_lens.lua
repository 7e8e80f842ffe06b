-- Depth of field: a speckled plate (5 cm x 6 cm) tilted 60° about the vertical, seen by a thin lens
-- (f = 50 mm at f/8, focused at 0.5 m) with OpenCV's rational + thin-prism distortion. The plate's
-- middle lies on the plane in focus and is sharp; its ends (about 0.478 m and 0.522 m away) are
-- blurred by disks of diameter c = A fx |1/u - 1/d| ≈ 6.3 px and 5.8 px (A = f/N = 6.25 mm,
-- fx = v / pixel size = 11111 px at v = 55.6 mm, the image distance of 0.5 m). A backdrop at 0.7 m
-- is blurred by 40 px. The camera matrix (fx = v/sx) and the ground truth are the chief ray's.
-- Camera.ThinLens and Distortion.Rational: docs/cameras.md.
-- Parameter: -D fnumber=<N> (default 8).
fnumber = fnumber or 8
camera = Camera.ThinLens { resolution = {640, 480}; pixelSize = {5e-6, 5e-6}; bitsPerPixel = 10;
  focalLength = 0.05; fNumber = fnumber; focusDistance = 0.5;
  distortion = Distortion.Rational { radial = {-0.5, 0.02, 0, 0.05, 0, 0.001};
                                     tangential = {2e-4, -1e-4}; thinPrism = {1e-3, 0, -8e-4, 0} } }
plate = Object.Simple {
  shape = Shape.Rectangle { size = {0.05, 0.06}; location = {0, 0, 0.5} };
  transform = rotate_y(degrees(60));
  shader = Shader.Constant { color = 0.9 };
  texture = Texture.File { fileName = "speckle.tif" } }
backdrop = Object.Simple {
  shape = Shape.Rectangle { size = {0.1, 0.08}; location = {0, 0, 0.7} };
  shader = Shader.Constant { color = 0.4 };
  texture = Texture.File { fileName = "speckle.tif" } }
