-- Figure 1 of Garcia et al. (PhotoMechanics 2013), the paper dicsynth follows: a speckled sphere of
-- radius 10 cm, 50 cm in front of a 1600 x 1200 camera with a 12 mm lens, 4.4 um pixels, a 90 % fill
-- factor, 10 bits per pixel and strong Brown distortion. The sphere and its texture are turned by
-- 35 degrees about the vertical axis through the sphere's centre (transform acts about the shape's
-- location), so the sphere stays in the middle of the view while its speckle moves.
-- Texture: speckle.tif beside this file, made by
--   dicsynth speckle -o scenes/speckle.tif --size 4096 2048 --radius 3 --density 0.5 --seed 1 --bits 8
-- (4096 texels around the sphere: about one texel per pixel at the centre of the view).
-- Render: build/dicsynth render scenes/figure1.lua -o out
-- The scene below is the paper's fragment, verbatim.
camera1 = Camera.Pinhole { resolution = {1600, 1200}; principalPoint = {800, 600}; focalLength = 0.012;
  pixelSize = {4.4e-6, 4.4e-6}; fillFactor = 0.9; bitsPerPixel = 10;
  distortion = Distortion.Brown { radial = {-0.13, -0.39, 1.20}; tangential = {1.1e-6, -1.2e-6}; }; };
object = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, 0.5}; };
  shader = Shader.Constant { color = {.2, .8, 1}; }; texture = Texture.File { fileName = "speckle.tif"; };
  transform = rotate_y(degrees(35)); };
