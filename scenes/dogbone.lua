-- A flat dogbone tensile specimen (Nurbs.dogbone: 10 cm long, 2 cm grips, a 3 cm x 1 cm gauge
-- section, 1.5 cm C² transitions) necking frame after frame, seen by a 1600 x 1200 camera 40 cm
-- away, without distortion, under constant shading. The speckle is glued on (u, v), so it follows
-- the specimen: the same (u, v) is the same material point in every frame, and the ground truth
-- of a frame pair is the mapping of the documented material points (Nurbs.dogbone's comment in
-- host/scene/nurbs_constructors.cpp):
--   x = (1 + strain) X,  y = Y (1 - 0.3 strain) (1 - necking bump(X)),  bump = a C² cubic
--   B-spline bump of length neckLength = 2 cm, 1 at the centre.
-- Parameters:
--   frame               necking = frame x 0.001: render --frames 0:10 for the necking sequence
--   -D necking=<n>      relative width reduction at the centre, instead of the frame's
--   -D strain=<e>       uniform axial engineering strain (default 0)
-- Texture: speckle.tif spans the whole specimen in u and the local width in v (in the gauge
-- section the texture is squeezed to half its height in the grips).
necking = necking or frame * 0.001
strain = strain or 0
camera = Camera.Pinhole { resolution = {1600, 1200}; focalLength = 0.012; pixelSize = {2.5e-6, 2.5e-6};
  bitsPerPixel = 8; };
specimen = Object.Simple {
  shape = Nurbs.dogbone { length = 0.1; width = 0.02; gaugeLength = 0.03; gaugeWidth = 0.01;
    transitionLength = 0.015; neckLength = 0.02; necking = necking; strain = strain;
    poissonRatio = 0.3; location = {0, 0, 0.4}; };
  shader = Shader.Constant { color = 0.9; };
  texture = Texture.File { fileName = "speckle.tif"; }; };
