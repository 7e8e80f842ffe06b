-- Point light and shadows: a matte sphere floats above a matte floor; the point light casts its
-- shadow on the floor (Lambert shading, inverse-square falloff, shadow rays). The floor is a large
-- Shape.Rectangle turned to lie horizontally (y is down, so "above" is -y).
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.012; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 12; position = {0, -0.25, -0.1}; lookAt = {0, 0.05, 0.6}; };
floor = Object.Simple {
  shape = Shape.Rectangle { size = {1.0, 1.0}; location = {0, 0.1, 0.6}; };
  shader = Shader.Lambert { color = 0.8; };
  texture = Texture.File { fileName = "speckle.tif"; };
  transform = rotate_x(degrees(90)); };
ball = Object.Simple {
  shape = Shape.Sphere { radius = 0.06; location = {0.02, 0.0, 0.55}; };
  shader = Shader.Lambert { color = {0.9, 0.9, 0.9}; }; };
sun = Light.Point { position = {-0.25, -0.4, 0.4}; intensity = 0.6; };
