-- A plate with a central hole under tension, deformed by a finite-element displacement field read
-- from a mesh (Field.load): the classic heterogeneous field for validating DIC near a stress
-- concentration. The specimen is the ring between the hole (radius 5 mm) and r = 25 mm of a thin
-- plate, an exact NURBS (rational quadratic circles around, cubic across), 20 cm in front of an
-- 800 x 600 camera. Frame 1 moves it by Kirsch's field for a far-field stress sigma / E = 1e-3
-- along x, sampled at the nodes of a 128 x 32 quadrilateral mesh in millimetres
-- (data/plate_hole.vtu, written by scripts/make_kirsch_field.py) and interpolated by the mesh's own
-- shape functions. Nurbs.deform fits the deformed surface to `tolerance` with the ring's own
-- (u, v); disp in frame 1's EXR is the field as rendered, fieldError the rendered minus the FE field.
-- Parameters:
--   -D tolerance=<m>    fit tolerance (default 2e-8 m: the FE field is only continuous across
--                       element edges, so a smooth fit needs many knots per element for less)
-- Example: dicsynth render scenes/plate_hole.lua --frames 0:1
tolerance = tolerance or 2e-8
camera = Camera.Pinhole { resolution = {800, 600}; focalLength = 0.016; pixelSize = {6.9e-6, 6.9e-6};
  bitsPerPixel = 10 }

-- The ring r in [a, b] as a NURBS: around (u), four rational quadratic quarter circles (corner
-- control points at distance r sqrt 2, weight sqrt 2 / 2); across (v), a cubic Bezier with evenly
-- spaced control points, so that r = a + (b - a) v exactly.
local a, b = 0.005, 0.025
local around = { {1, 0, 1}, {1, 1, math.sqrt(0.5)}, {0, 1, 1}, {-1, 1, math.sqrt(0.5)}, {-1, 0, 1},
                 {-1, -1, math.sqrt(0.5)}, {0, -1, 1}, {1, -1, math.sqrt(0.5)}, {1, 0, 1} }
local points, weights = {}, {}
for _, c in ipairs(around) do
  for j = 0, 3 do
    local r = a + (b - a) * j / 3
    points[#points + 1] = {r * c[1], r * c[2], 0}
    weights[#weights + 1] = c[3]
  end
end
local ring = Shape.Nurbs { degree = {2, 3}; knotsU = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  knotsV = {0, 0, 0, 0, 1, 1, 1, 1}; controlPoints = points; weights = weights; location = {0, 0, 0.2} }

specimen = Object.Simple {
  shape = frame >= 1 and Nurbs.deform { surface = ring; tolerance = tolerance;
    displacement = Field.load { fileName = "data/plate_hole.vtu"; array = "displacement"; scale = 1e-3 } } or ring;
  shader = Shader.Constant { color = 0.9 };
  -- u runs around (~94 mm at mid radius), v across (20 mm): aspect = v length / u length there.
  texture = Texture.Speckle { radius = 0.0025; density = 0.5; aspect = 0.21; seed = 7 } }
