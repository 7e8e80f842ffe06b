// Figure 1 for POV-Ray 3.7, for the speed comparison of bench/bench_process.sh only (not an
// equivalent image: POV-Ray has no Brown distortion and filters its texture differently): a sphere
// of radius 0.1 m at 0.5 m, its speckle texture (scenes/speckle.tif, copied beside the output by the
// script) mapped spherically and turned 35° about the vertical axis, seen by a 1600 × 1200 camera
// with the 12 mm lens and 4.4 µm pixels of scenes/figure1.lua: horizontal field of view
// 2·atan(1600·4.4e-6 / 2 / 0.012) = 32.77°. Constant shading (ambient only), no light, like
// Shader.Constant.
global_settings { assumed_gamma 1.0 }
camera {
  perspective
  location <0, 0, 0>
  direction <0, 0, 1>
  right x * 1600 / 1200
  up y
  angle 32.77
}
sphere {
  <0, 0, 0>, 0.1
  texture {
    pigment { image_map { tiff "speckle.tif" map_type 1 interpolate 4 } }
    finish { ambient 1 diffuse 0 }
  }
  rotate <0, 35, 0>
  translate <0, 0, 0.5>
}
