-- Specular highlights and metals, as DIC users meet them: a speckled plate with a Phong clear coat,
-- a speckle-painted GGX metal sphere (rough steel) and a polished Blinn-Phong sphere, lit by two
-- point lights, a spot light and a little ambient light. Highlights saturate the sensor where a
-- light's mirror image falls, exactly where DIC correlation fails on real specimens.
-- Formulas and parameters: host/reflectance/ and docs/reflectance.md.
-- Render: build/dicsynth render scenes/specular.lua -o out
camera = Camera.Pinhole { resolution = {640, 480}; focalLength = 0.008; pixelSize = {7.4e-6, 7.4e-6};
  bitsPerPixel = 12; exposure = 1.5; position = {0, -0.05, 0}; lookAt = {0, 0, 0.6}; };
plate = Object.Simple {
  shape = Shape.Rectangle { size = {0.5, 0.4}; location = {0, 0, 0.65}; };
  shader = Shader.Phong { color = 0.6; specular = 0.2; shininess = 40; };
  texture = Texture.File { fileName = "speckle.tif"; };
  transform = rotate_x(degrees(-15)) * rotate_y(degrees(10)); };
steel = Object.Simple {
  shape = Shape.Sphere { radius = 0.06; location = {0.07, 0.0, 0.55}; };
  shader = Shader.GGX { color = 0.25; roughness = 0.25; f0 = 0.56; };
  texture = Texture.File { fileName = "speckle.tif"; }; };
bead = Object.Simple {
  shape = Shape.Sphere { radius = 0.035; location = {-0.09, 0.03, 0.52}; };
  shader = Shader.BlinnPhong { color = 0.4; specular = 0.5; shininess = 200; }; };
key = Light.Point { position = {-0.15, -0.25, 0.2}; intensity = 0.15; };
fill = Light.Point { position = {0.2, -0.1, 0.1}; intensity = 0.05; };
spot = Light.Spot { position = {0.05, -0.3, 0.35}; lookAt = {-0.05, 0.05, 0.65};
  innerAngle = degrees(8); outerAngle = degrees(14); intensity = 0.1; };
sky = Light.Ambient { intensity = 0.04; };
