-- An infinite speckled ground plane seen at a grazing angle: Shape.Plane repeats its texture every
-- tileSize (here 40 cm x 40 cm), so the view shows many tiles shrinking towards the horizon. Tests the
-- (u, v) wrap (u = fract(x / w + 1/2)) and the far, oblique hits where precision matters most.
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.008; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 16; };
ground = Object.Simple {
  shape = Shape.Plane { tileSize = {0.4, 0.4}; location = {0, 0.1, 0}; };
  shader = Shader.Constant { color = 0.8; };
  texture = Texture.File { fileName = "speckle.tif"; };
  transform = rotate_x(degrees(-80)); };
