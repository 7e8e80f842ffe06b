-- Triangles: two of them form a textured square (their per-vertex uv glue one speckle image across
-- both), a third, untextured, hangs in front and casts a shadow on the square under a point light.
-- Shape.Triangle vertices are relative to its location; (u, v) blends the vertices' uv.
camera = Camera.Pinhole { resolution = {640, 480}; focalLength = 0.006; pixelSize = {5e-6, 5e-6}; };
lowerLeft = Object.Simple {
  shape = Shape.Triangle { vertices = {{-0.1, -0.1, 0}, {0.1, 0.1, 0}, {-0.1, 0.1, 0}};
    uv = {{0, 0}, {1, 1}, {0, 1}}; location = {0, 0, 0.5}; };
  shader = Shader.Lambert { color = 0.9; }; texture = Texture.File { fileName = "speckle.tif"; }; };
upperRight = Object.Simple {
  shape = Shape.Triangle { vertices = {{-0.1, -0.1, 0}, {0.1, -0.1, 0}, {0.1, 0.1, 0}};
    uv = {{0, 0}, {1, 0}, {1, 1}}; location = {0, 0, 0.5}; };
  shader = Shader.Lambert { color = 0.9; }; texture = Texture.File { fileName = "speckle.tif"; }; };
occluder = Object.Simple {
  shape = Shape.Triangle { vertices = {{-0.03, -0.02, 0}, {0.04, -0.03, 0}, {0.0, 0.05, 0}};
    location = {0.02, 0.01, 0.42}; };
  shader = Shader.Lambert { color = {0.9, 0.3, 0.2}; }; };
light = Light.Point { position = {0.15, -0.2, 0.1}; intensity = 0.6; };
