-- A non-affine homography: the speckled rectangle of rectangle.lua under a projective transform
-- (bottom row 2, 1.5, 0, 1 in the rectangle's frame), which maps lines to lines but keystones the
-- specimen and its texture, with a sphere beside it under another projective map. The paper allows
-- any homography per object; rays are mapped into object space (docs/cameras.md, "Conventions").
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.010; pixelSize = {5e-6, 5e-6}; };
keystone = homography { 1,   0,   0, 0,
                        0,   1,   0, 0,
                        0,   0,   1, 0,
                        2.0, 1.5, 0, 1 };
specimen = Object.Simple {
  shape = Shape.Rectangle { size = {0.1, 0.075}; location = {-0.02, 0, 0.4}; };
  shader = Shader.Constant { color = 0.9; };
  texture = Texture.File { fileName = "speckle.tif"; };
  transform = keystone; };
egg = Object.Simple {
  shape = Shape.Sphere { radius = 0.02; location = {0.055, 0.0, 0.38}; };
  shader = Shader.Constant { color = 0.7; };
  texture = Texture.File { fileName = "speckle.tif"; };
  transform = homography { 1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 12, 0, 1 }; };
