-- The classic 2D-DIC specimen: a flat speckled rectangle (10 cm x 7.5 cm) facing an 800 x 600 camera
-- 40 cm away, without distortion, under constant shading. Shape.Rectangle lies in its local xy-plane,
-- facing -z; (u, v) = (0, 0) is its top-left corner as the camera sees it.
-- Parameter: -D shift=<metres> translates the specimen along x (a rigid-body motion test; default 0).
shift = shift or 0
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.016; pixelSize = {5e-6, 5e-6};
  bitsPerPixel = 8; };
specimen = Object.Simple {
  shape = Shape.Rectangle { size = {0.1, 0.075}; location = {shift, 0, 0.4}; };
  shader = Shader.Constant { color = 0.9; };
  texture = Texture.File { fileName = "speckle.tif"; }; };
