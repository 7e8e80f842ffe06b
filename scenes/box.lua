-- A speckled box (12 x 8 x 10 cm) turned to show three faces, lit by one point light (Lambert).
-- Box (u, v): a 3 x 2 atlas of the six faces (docs/cameras.md, "Surface parameters (u, v) per shape"), so the one speckle image covers all
-- faces. The camera looks at it from above-left with position/lookAt; its up vector is -y (y down).
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.012; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 12; position = {-0.25, -0.2, -0.1}; lookAt = {0, 0, 0.5};
  distortion = Distortion.Brown { radial = {-0.05, 0.02}; }; };
box = Object.Simple {
  shape = Shape.Box { size = {0.12, 0.08, 0.10}; location = {0, 0, 0.5}; };
  shader = Shader.Lambert { color = 0.85; };
  texture = Texture.File { fileName = "speckle.tif"; };
  transform = rotate_y(degrees(-20)) * rotate_x(degrees(10)); };
lamp = Light.Point { position = {-0.3, -0.5, 0.1}; intensity = 1.7; };
