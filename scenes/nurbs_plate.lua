-- A speckled plate (10 cm x 7.5 cm) built as a NURBS surface by Nurbs.plate, facing a 1600 x 1200
-- camera 50 cm away, without distortion, under constant shading: the classic 2D-DIC specimen made
-- deformable. (u, v) = (0, 0) is its top-left corner as the camera sees it (as on Shape.Rectangle),
-- and the speckle is glued on (u, v): it stretches and bends with the plate, so the same (u, v) is
-- the same material point in every rendering.
-- Parameters:
--   -D strain=<e>       uniaxial engineering strain along x (default 0); the plate contracts along
--                       y by 0.3 e (Poisson ratio 0.3): the texture follows exactly
--   -D curvature=<1/m>  bends the plate about its vertical axis without stretching it, the edges
--                       away from the camera (default 0: flat, exactly planar). With 8 spans along
--                       x the bent surface is within 3.5e-3 a^4 / curvature of the cylinder
--                       (a = curvature x 0.1 / 8): 6e-9 m at curvature = 4, where the fake
--                       strain of its parametrization stays below 1e-7.
-- Example: dicsynth render scenes/nurbs_plate.lua -D strain=0.002 -D curvature=4
strain = strain or 0
curvature = curvature or 0
camera = Camera.Pinhole { resolution = {1600, 1200}; focalLength = 0.016; pixelSize = {2.5e-6, 2.5e-6};
  bitsPerPixel = 8; };
plate = Object.Simple {
  shape = Nurbs.plate { size = {0.1, 0.075}; strain = {strain, -0.3 * strain};
    curvature = curvature; spans = {8, 4}; location = {0, 0, 0.5}; };
  shader = Shader.Constant { color = 0.9; };
  texture = Texture.File { fileName = "speckle.tif"; }; };
