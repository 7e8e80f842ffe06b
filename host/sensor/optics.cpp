// Optical post-processors: blur kernels, vignetting and dust (optics.h).
#include "sensor/optics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "core/parallel.h"

namespace dicsynth {
namespace {

double normalCdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

void normalize(std::vector<double>& w) {
  double sum = 0;
  for (double v : w) sum += v;
  for (double& v : w) v /= sum;
}

int clampIndex(int i, int n) { return std::clamp(i, 0, n - 1); }

}  // namespace

std::vector<double> gaussianKernel(double sigma_px) {
  DS_CHECK(sigma_px > 0 && std::isfinite(sigma_px), "Gaussian blur sigma must be > 0");
  const int radius = int(std::ceil(6.0 * sigma_px));
  std::vector<double> w(std::size_t(2 * radius + 1));
  for (int k = -radius; k <= radius; ++k)
    w[std::size_t(k + radius)] = normalCdf((k + 0.5) / sigma_px) - normalCdf((k - 0.5) / sigma_px);
  normalize(w);
  return w;
}

std::vector<double> diskKernel(double radius_px) {
  DS_CHECK(radius_px > 0 && std::isfinite(radius_px), "defocus disk radius must be > 0");
  // A disk of radius <= 1/2 around the pixel centre lies inside its own pixel: the exact kernel is
  // the identity. (The point sampling below found no sample inside disks under 0.011 px, the
  // distance of the nearest sample, and normalized a kernel of zeros: an all-black image, found by
  // the sensor audit of 2026-11-28, e.g. radius_px 0.04 at --downscale 4.)
  if (radius_px <= 0.5) return {1.0};
  const int R = int(std::ceil(radius_px + 0.5));
  const int n = 2 * R + 1;
  const int sub = 64;
  const double r2 = radius_px * radius_px;
  std::vector<double> w(std::size_t(n) * n);
  for (int j = -R; j <= R; ++j)
    for (int i = -R; i <= R; ++i) {
      // Nearest and farthest points of the pixel square from the disk's centre.
      const double nx = std::max(0.0, std::fabs(double(i)) - 0.5), ny = std::max(0.0, std::fabs(double(j)) - 0.5);
      const double fx = std::fabs(double(i)) + 0.5, fy = std::fabs(double(j)) + 0.5;
      double area;
      if (fx * fx + fy * fy <= r2) area = 1.0;
      else if (nx * nx + ny * ny >= r2) area = 0.0;
      else {
        int inside = 0;
        for (int b = 0; b < sub; ++b)
          for (int a = 0; a < sub; ++a) {
            const double x = i - 0.5 + (a + 0.5) / sub, y = j - 0.5 + (b + 0.5) / sub;
            inside += x * x + y * y < r2;
          }
        area = double(inside) / double(sub * sub);
      }
      w[std::size_t(j + R) * n + std::size_t(i + R)] = area;
    }
  normalize(w);
  return w;
}

std::vector<double> applyBlur(const std::vector<double>& image, int width, int height, const Blur& blur) {
  DS_CHECK(image.size() == std::size_t(width) * std::size_t(height), "blur: image size");
  std::vector<double> out(image.size());
  if (blur.kind == BlurKind::Gaussian) {
    // Separable: rows into `tmp`, then columns into `out`.
    const std::vector<double> w = gaussianKernel(blur.sigma_px);
    const int R = int(w.size() / 2);
    std::vector<double> tmp(image.size());
    parallelFor(std::size_t(height), [&](std::size_t y) {
      const double* row = &image[y * std::size_t(width)];
      for (int x = 0; x < width; ++x) {
        double s = 0;
        for (int k = -R; k <= R; ++k) s += w[std::size_t(k + R)] * row[clampIndex(x + k, width)];
        tmp[y * std::size_t(width) + std::size_t(x)] = s;
      }
    });
    parallelFor(std::size_t(height), [&](std::size_t y) {
      for (int x = 0; x < width; ++x) {
        double s = 0;
        for (int k = -R; k <= R; ++k)
          s += w[std::size_t(k + R)] * tmp[std::size_t(clampIndex(int(y) + k, height)) * std::size_t(width) + std::size_t(x)];
        out[y * std::size_t(width) + std::size_t(x)] = s;
      }
    });
    return out;
  }
  const std::vector<double> w = diskKernel(blur.radius_px);
  const int n = int(std::lround(std::sqrt(double(w.size()))));
  const int R = n / 2;
  parallelFor(std::size_t(height), [&](std::size_t yIndex) {
    const int y = int(yIndex);
    for (int x = 0; x < width; ++x) {
      double s = 0;
      for (int j = -R; j <= R; ++j) {
        const double* row = &image[std::size_t(clampIndex(y + j, height)) * std::size_t(width)];
        const double* wr = &w[std::size_t(j + R) * std::size_t(n)];
        for (int i = -R; i <= R; ++i)
          if (wr[i + R] != 0) s += wr[i + R] * row[clampIndex(x + i, width)];
      }
      out[yIndex * std::size_t(width) + std::size_t(x)] = s;
    }
  });
  return out;
}

double vignettingFactor(const Vignetting& v, const VignettingGeometry& g, double x_px, double y_px) {
  const double dx = x_px - g.cx_px, dy = y_px - g.cy_px;
  if (v.kind == VignettingKind::Cos4) {
    const double rx = dx * g.pixelSizeX_m / g.focalLength_m, ry = dy * g.pixelSizeY_m / g.focalLength_m;
    const double t = 1.0 + rx * rx + ry * ry;  // 1 + tan²θ = 1/cos²θ
    return 1.0 / (t * t);
  }
  const double halfDiagonal = 0.5 * std::hypot(double(g.width_px), double(g.height_px));
  const double rho2 = (dx * dx + dy * dy) / (halfDiagonal * halfDiagonal);
  double factor = 1.0, power = 1.0;
  for (double a : v.coefficients) {
    power *= rho2;
    factor += a * power;
  }
  return std::max(0.0, factor);
}

double dustTransmission(const DustBlob& blob, double x_px, double y_px) {
  const double d = std::hypot(x_px - blob.x_px, y_px - blob.y_px);
  if (d >= blob.radius_px) return 1.0;
  return 1.0 - blob.opacity * 0.5 * (1.0 + std::cos(std::numbers::pi * d / blob.radius_px));
}

}  // namespace dicsynth
