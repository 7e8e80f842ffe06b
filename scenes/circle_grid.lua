-- An asymmetric circle grid (OpenCV's CALIB_CB_ASYMMETRIC_GRID layout, 4 x 11 dots, spacing 10 mm:
-- rows 10 mm apart, dots 20 mm apart in a row, odd rows shifted by 10 mm; dot radius 3 mm), 42 cm
-- in front of a 1280 x 960 camera with Brown distortion, tilted by 25 degrees about its vertical axis
-- and 10 degrees about its horizontal one, so that perspective shows.
-- Detect with cv::findCirclesGrid(image, {4, 11}, centres, CALIB_CB_ASYMMETRIC_GRID); the ground
-- truth (out/camera.features.csv) gives each dot's projected centre, which under perspective is
-- not the centroid of the dot's image that the detector finds (docs/calibration.md).
-- Render: build/dicsynth render scenes/circle_grid.lua -o out
camera = Camera.Pinhole { resolution = {1280, 960}; focalLength = 0.012; pixelSize = {4.4e-6, 4.4e-6};
  bitsPerPixel = 8; distortion = Distortion.Brown { radial = {-0.1, 0.05, 0}; tangential = {1e-4, 2e-4} } }
-- The target frame's origin is the first dot's centre; centre the 70 x 100 mm pattern on the axis.
dots = Target.CircleGrid { circles = {4, 11}; spacing = 0.01; asymmetric = true; radius = 0.003;
  border = 0.008;
  transform = translate(0, 0, 0.42) * rotate_y(degrees(25)) * rotate_x(degrees(10)) * translate(-0.035, -0.05, 0) }
