#pragma once
// Valid NURBS surfaces for the NURBS tests (the scene's validateNurbs is not needed: each builder
// makes counts, knots and weights consistent by construction), and long double helpers.
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/scene.h"
#include "nurbs/nurbs_surface.h"

namespace dicsynth::test {

// Knot vector of degree p clamped at [a, b] with the given interior knots (a value repeated k times
// has multiplicity k).
inline std::vector<double> clampedKnots(int p, const std::vector<double>& interior, double a = 0, double b = 1) {
  std::vector<double> U(std::size_t(p + 1), a);
  U.insert(U.end(), interior.begin(), interior.end());
  U.insert(U.end(), std::size_t(p + 1), b);
  return U;
}

// Greville abscissae (U[i+1] + … + U[i+p]) / p: a B-spline whose control values are these is the
// identity t ↦ t (linear precision), so x(u) is linear in the knot parameter.
inline std::vector<double> greville(const std::vector<double>& U, int p) {
  const int count = int(U.size()) - p - 1;
  std::vector<double> g(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    double sum = 0;
    for (int k = 1; k <= p; ++k) sum += U[std::size_t(i + k)];
    g[std::size_t(i)] = sum / p;
  }
  return g;
}

inline NurbsSurface makeSurface(int p, int q, std::vector<double> U, std::vector<double> V,
                                const std::function<dvec3(int, int)>& point,
                                const std::function<double(int, int)>& weight = nullptr) {
  NurbsSurface s;
  s.degreeU = p;
  s.degreeV = q;
  s.countU = int(U.size()) - p - 1;
  s.countV = int(V.size()) - q - 1;
  s.knotsU = std::move(U);
  s.knotsV = std::move(V);
  for (int i = 0; i < s.countU; ++i)
    for (int j = 0; j < s.countV; ++j) {
      s.controlPoints.push_back(point(i, j));
      s.weights.push_back(weight ? weight(i, j) : 1.0);
    }
  return s;
}

// Graph z = f(x, y) over [x0, x0 + w] × [y0, y0 + h]: control points at the Greville abscissae, so
// x = x0 + w u and y = y0 + h v exactly (u, v normalized), and z is the spline of the values
// height(i, j). Polynomial (weights 1).
inline NurbsSurface graphSurface(int p, int q, const std::vector<double>& U, const std::vector<double>& V,
                                 dvec2 origin, dvec2 extent, const std::function<double(int, int)>& height) {
  const std::vector<double> gu = greville(U, p), gv = greville(V, q);
  const double u0 = U[std::size_t(p)], u1 = U[U.size() - std::size_t(p) - 1];
  const double v0 = V[std::size_t(q)], v1 = V[V.size() - std::size_t(q) - 1];
  return makeSurface(p, q, U, V, [&](int i, int j) {
    return dvec3(origin.x + extent.x * (gu[std::size_t(i)] - u0) / (u1 - u0),
                 origin.y + extent.y * (gv[std::size_t(j)] - v0) / (v1 - v0), height(i, j));
  });
}

// A bicubic flat plate in z = 0, `spans` × `spans` non-uniform spans, centred on the origin.
inline NurbsSurface plateSurface(double width, double height, int spans) {
  std::vector<double> interior;
  for (int k = 1; k < spans; ++k) interior.push_back((k + 0.15 * std::sin(3.0 * k)) / spans);
  const auto U = clampedKnots(3, interior);
  return graphSurface(3, 3, U, U, {-width / 2, -height / 2}, {width, height}, [](int, int) { return 0.0; });
}

// Cylinder x² + z² = R² (axis y) between angles φ0 and φ1 (point (R sin φ, y, −R cos φ): φ = 0
// faces −z), exact rational quadratic arcs of at most 90° per span; linear along y ∈ [y0, y1]
// (degree `axisDegree`, one span).
inline NurbsSurface cylinderSurface(double R, double phi0, double phi1, int spans, double y0, double y1,
                                    int axisDegree = 1) {
  std::vector<double> interior;
  for (int k = 1; k < spans; ++k) interior.insert(interior.end(), 2, double(k) / spans);
  const auto U = clampedKnots(2, interior);
  const auto V = clampedKnots(axisDegree, {});
  const double delta = (phi1 - phi0) / spans;
  return makeSurface(
      2, axisDegree, U, V,
      [&](int i, int j) {
        const double phi = phi0 + 0.5 * i * delta;
        const double r = i % 2 ? R / std::cos(delta / 2) : R;  // the tangents' intersection
        return dvec3(r * std::sin(phi), y0 + (y1 - y0) * j / axisDegree, -r * std::cos(phi));
      },
      [&](int i, int) { return i % 2 ? std::cos(delta / 2) : 1.0; });
}

// The octant x, y, z ≥ 0 of the sphere of radius R: a surface of revolution, biquadratic, whose
// u = 0 edge collapses into the pole (0, 0, R).
inline NurbsSurface sphereOctantSurface(double R) {
  const double c = std::sqrt(0.5);
  const double profileR[3] = {0, R, R}, profileZ[3] = {R, R, 0}, profileW[3] = {1, c, 1};
  const double circleX[3] = {1, 1, 0}, circleY[3] = {0, 1, 1}, circleW[3] = {1, c, 1};
  const auto U = clampedKnots(2, {});
  return makeSurface(
      2, 2, U, U, [&](int i, int j) { return dvec3(profileR[i] * circleX[j], profileR[i] * circleY[j], profileZ[i]); },
      [&](int i, int j) { return profileW[i] * circleW[j]; });
}

// A quarter disk of radius R in z = 0 (x, y ≥ 0) whose u = 0 edge collapses into the centre:
// degree 1 radially, an exact quadratic arc around.
inline NurbsSurface quarterDiskSurface(double R) {
  const double c = std::sqrt(0.5);
  const double circleX[3] = {1, 1, 0}, circleY[3] = {0, 1, 1}, circleW[3] = {1, c, 1};
  return makeSurface(
      1, 2, clampedKnots(1, {}), clampedKnots(2, {}),
      [&](int i, int j) { return dvec3(i * R * circleX[j], i * R * circleY[j], 0); },
      [&](int, int j) { return circleW[j]; });
}

// A scene object holding the surface (Lambert, constant texture 0.5), as the scene loader builds it.
inline Object nurbsObject(const std::string& name, const NurbsSurface& surface, dvec3 location, dmat4 transform = dmat4(1.0)) {
  Object o;
  o.name = name;
  o.where = {"scene.lua", 7};
  o.shape.where = {"scene.lua", 7};
  o.shape.location_m = location;
  o.shape.nurbs = std::make_shared<NurbsSurface>(surface);
  o.shader.model = reflectance::Lambert{};
  o.texture.model = textures::Constant{0.5};
  o.transform = transform;
  return o;
}

}  // namespace dicsynth::test
