#pragma once
// The optical post-processors: they act on the radiance that reaches the sensor, before any
// electron is counted (sensor.h applies them in the order blur → vignetting → dust). Each takes and
// returns a row-major image of width × height doubles. Pixel positions are OpenCV's (centre of the
// top-left pixel at (0, 0)); lengths are in pixels of the image given (the caller converts the
// scene's values for --downscale).
#include <vector>

#include "model/sensor_model.h"

namespace dicsynth {

// The kernel of Blur.Gaussian along one axis: w[k + R] for k in -R..R, R = ceil(6σ):
//   w[k] ∝ Φ((k + ½)/σ) − Φ((k − ½)/σ)
// (the mass of the continuous Gaussian PSF over pixel k, so even σ ≪ 1 px keeps its mass), scaled
// to sum 1 (the mass beyond 6σ, 2e-9, is given back to the kernel: blur conserves light).
std::vector<double> gaussianKernel(double sigma_px);

// The kernel of Blur.Disk (a defocus disk of radius r): a (2R+1)² table, R = ceil(r + ½), whose
// entry (i, j) is the area of pixel (i - R, j - R) inside the disk, measured on a 64 × 64 grid of
// points per pixel that the disk's edge crosses (exact 1 or 0 inside/outside), scaled to sum 1.
std::vector<double> diskKernel(double radius_px);

// Convolution with the blur's kernel; pixels beyond the border repeat the border pixel (the scene
// continues; no dark frame fades in). Each output pixel is a fixed-order sum: thread-independent.
std::vector<double> applyBlur(const std::vector<double>& image, int width, int height, const Blur& blur);

// The vignetting factor at pixel (x, y):
//   Cos4:   cos⁴θ = 1 / (1 + (r/f)²)², r the distance of the pixel centre from the principal point
//           on the sensor (metres, pixelSize), f the focal length: the natural fall-off of a lens.
//   Radial: max(0, 1 + a1 ρ² + a2 ρ⁴ + a3 ρ⁶), ρ = distance from the principal point in px divided
//           by the half-diagonal of the image, sqrt(w² + h²)/2 (ρ ≈ 1 in a corner).
struct VignettingGeometry {
  int width_px = 0, height_px = 0;
  double cx_px = 0, cy_px = 0;            // principal point
  double pixelSizeX_m = 0, pixelSizeY_m = 0;
  double focalLength_m = 0;
};
double vignettingFactor(const Vignetting& v, const VignettingGeometry& g, double x_px, double y_px);

// Transmission of one dust blob at a pixel centre: 1 − opacity · (1 + cos(π d/radius))/2 for
// d < radius, else 1 (a raised-cosine shadow: opacity at its centre, soft edge, none beyond radius).
double dustTransmission(const DustBlob& blob, double x_px, double y_px);

}  // namespace dicsynth
