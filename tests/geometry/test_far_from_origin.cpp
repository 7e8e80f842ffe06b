// Objects far from the world origin keep their accuracy (geometry/object_map.h): the CPU reference's
// hits on a rotated sphere and a rotated box at offsets up to 1e7 m, against independent oracles in
// long double that intersect the shape in its own frame, mapped there from the scene's numbers as
// written (the transform inverted by cofactors, the camera's offset from the shape taken first).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "cpu/trace.h"
#include "scene/scene.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

using LD = long double;
struct V3 {
  LD x, y, z;
};
V3 mul(const LD m[3][3], V3 v) {  // m[row][col]
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}
LD dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

// The inverse of a 3×3 matrix by cofactors, in long double.
void invert(const LD a[3][3], LD out[3][3]) {
  const LD det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      out[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;  // cyclic cofactors carry their sign
    }
}

std::string g17(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// A point as the scene language reads it back to the same doubles.
std::string luaVector(dvec3 p) { return "{" + g17(p.x) + ", " + g17(p.y) + ", " + g17(p.z) + "}"; }

// The far scenes' camera (prepare needs one; the tests trace their own rays).
const std::string kCamera = "cam = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.01; pixelSize = {1e-5, 1e-5} }\n";

// Tolerance: both sides compute in double from the same numbers; the oracles' own error is ~1e-19.
// The CPU path's map and intersection are a few dozen roundings of 2⁻⁵³ ≈ 1.1e-16, relative to the
// sizes of the object frame (the shape, the camera within 6 of its sizes), divided by cos θ ≥ 0.3 at
// the hit: ≲ 32 · 1.1e-16 / 0.3 ≈ 1.2e-14. 1e-12 leaves a margin of ~80, and is ~1e5 below what the
// map formed as A⁻¹p − A⁻¹b lost at 5e6 m (7e-7 relative, the shape audit of 2026-11-28).
constexpr double kTolerance = 1e-12;

// One random far scene: a shape (its Lua constructor, without location) at `location` under
// `rotation`, prepared; and what the oracle needs, computed apart in long double: the rotation's
// inverse and the camera's offset from the shape's origin in the shape's frame.
struct FarScene {
  PreparedScene prepared;
  LD Rinv[3][3];
  V3 eye;  // the camera, in the shape's frame

  V3 direction(dvec3 d) const { return mul(Rinv, {LD(d.x), LD(d.y), LD(d.z)}); }
};

FarScene farScene(const test::TempFolder& dir, const std::string& shape, dvec3 location, const dmat4& rotation, dvec3 eye) {
  std::string h;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) h += (h.empty() ? "" : ", ") + g17(rotation[col][row]);
  const std::string path = dir.write(
      "far.lua", kCamera + "thing = Object.Simple { shape = " + shape + "; location = " + luaVector(location) +
                     " }; transform = homography{" + h + "} }\n");
  FarScene f;
  f.prepared = prepareScene(loadScene(path, {}), {1});
  LD R[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R[r][c] = rotation[c][r];
  invert(R, f.Rinv);
  // The camera's offset from the shape: exact in long double (64-bit significands).
  f.eye = mul(f.Rinv, {LD(eye.x) - LD(location.x), LD(eye.y) - LD(location.y), LD(eye.z) - LD(location.z)});
  return f;
}

}  // namespace

TEST_CASE("far from the origin: a rotated sphere's hits match a long-double oracle at offsets up to 1e7 m") {
  test::TempFolder dir;
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(-1, 1);
  int checked = 0, hitMissDisagreements = 0, depthDisagreements = 0, uvDisagreements = 0;
  double worstDepth = 0, worstUv = 0;
  for (int scene = 0; scene < 120; ++scene) {
    const double offset = scene < 10 ? 0.0 : std::pow(10.0, 1 + 6 * std::abs(unit(rng)));  // up to 1e7 m
    const double radius = std::pow(10.0, -3 + 3 * std::abs(unit(rng)));                   // 1 mm to 1 m
    const dvec3 location = offset * glm::normalize(dvec3(unit(rng), unit(rng), unit(rng)));
    // A random rotation (its matrix rounded to double: the oracle inverts the rounded one).
    const dmat4 rotation = glm::rotate(dmat4(1), 3 * unit(rng), glm::normalize(dvec3(unit(rng), unit(rng), unit(rng))));
    const dvec3 view = glm::normalize(dvec3(unit(rng), unit(rng), unit(rng)));  // from the sphere to the camera
    const dvec3 eye = location + (2 + 3 * std::abs(unit(rng))) * radius * view;
    const FarScene far = farScene(dir, "Shape.Sphere { radius = " + g17(radius), location, rotation, eye);
    const V3 o = far.eye;
    for (int k = 0; k < 40; ++k) {
      // Aim at a point of the sphere's visible cap (within ~50° of the view direction).
      const dvec3 target = location + radius * glm::normalize(view + 0.8 * dvec3(unit(rng), unit(rng), unit(rng)));
      const dvec3 d = target - eye;
      const V3 dl = far.direction(d);
      // |o + s d|² = r²: the nearer root by the stable form q = −(b + sign(b)√disc), s = c/q.
      const LD a = dot(dl, dl), b = dot(o, dl), c = dot(o, o) - LD(radius) * LD(radius);
      const LD disc = b * b - a * c;
      cpu::SurfaceHit hit;
      const bool cpuHit = cpu::traceNearest(far.prepared, eye, d, hit);
      if (disc <= 0) {
        hitMissDisagreements += cpuHit ? 1 : 0;
        continue;
      }
      const LD q = -(b + std::copysign(std::sqrt(disc), b));
      const LD s = std::min(c / q, q / a);
      const V3 x = {o.x + s * dl.x, o.y + s * dl.y, o.z + s * dl.z};
      const LD cosTheta = std::abs(dot(x, dl)) / (std::sqrt(dot(x, x)) * std::sqrt(a));
      const LD sinPolar = std::sqrt(x.x * x.x + x.z * x.z) / LD(radius);
      if (cosTheta < 0.3 || sinPolar < 0.05) continue;  // grazing, or near a pole where u turns fast
      ++checked;
      if (!cpuHit) {
        ++hitMissDisagreements;
        continue;
      }
      // docs/cameras.md: u = ½ + atan2(x, −z)/2π, v = polar angle from the −y pole / π.
      const LD pi = std::acos(LD(-1));
      const LD u = 0.5L + std::atan2(x.x, -x.z) / (2 * pi), v = std::acos(-x.y / std::sqrt(dot(x, x))) / pi;
      const double depthError = double(std::abs(LD(hit.t) - s) / s);
      const double du = std::abs(double(LD(hit.uv.x) - u)), dv = std::abs(double(LD(hit.uv.y) - v));
      const double uvError = std::max(std::min(du, 1 - du), dv);  // u is periodic
      worstDepth = std::max(worstDepth, depthError);
      worstUv = std::max(worstUv, uvError);
      if (!(depthError <= kTolerance)) ++depthDisagreements;
      if (!(uvError <= kTolerance)) ++uvDisagreements;
    }
  }
  INFO("worst relative depth error " << worstDepth << ", worst uv error " << worstUv);
  CHECK(checked > 2000);
  CHECK(hitMissDisagreements == 0);
  CHECK(depthDisagreements == 0);
  CHECK(uvDisagreements == 0);
}

TEST_CASE("far from the origin: a rotated box's hits match a long-double slab oracle at offsets up to 1e7 m") {
  // The same promise for a flat kind: the box's faces in its frame, intersected by slabs in long
  // double (relative depth, rays at cos θ ≥ 0.3); rays whose hit lies within 1e-6 of the box's
  // size of an edge are left out (either face is then right within rounding).
  test::TempFolder dir;
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> unit(-1, 1);
  int checked = 0, hitMissDisagreements = 0, depthDisagreements = 0, normalDisagreements = 0;
  double worstDepth = 0;
  for (int scene = 0; scene < 80; ++scene) {
    const double offset = scene < 8 ? 0.0 : std::pow(10.0, 1 + 6 * std::abs(unit(rng)));
    const dvec3 half = std::pow(10.0, -3 + 3 * std::abs(unit(rng))) * dvec3(1, 0.5 + 0.5 * std::abs(unit(rng)), 0.7);
    const dvec3 location = offset * glm::normalize(dvec3(unit(rng), unit(rng), unit(rng)));
    const dmat4 rotation = glm::rotate(dmat4(1), 3 * unit(rng), glm::normalize(dvec3(unit(rng), unit(rng), unit(rng))));
    const dvec3 view = glm::normalize(dvec3(unit(rng), unit(rng), unit(rng)));
    const double size = glm::length(half);
    const dvec3 eye = location + (3 + 3 * std::abs(unit(rng))) * size * view;
    const FarScene far = farScene(
        dir, "Shape.Box { size = {" + g17(2 * half.x) + ", " + g17(2 * half.y) + ", " + g17(2 * half.z) + "}", location,
        rotation, eye);
    const V3 o = far.eye;
    const LD hx[3] = {LD(2 * half.x) / 2, LD(2 * half.y) / 2, LD(2 * half.z) / 2};  // as the scene states them
    for (int k = 0; k < 40; ++k) {
      const dvec3 target = location + 1.2 * dvec3(half.x * unit(rng), half.y * unit(rng), half.z * unit(rng));
      const dvec3 d = target - eye;
      const V3 dl = far.direction(d);
      const LD oo[3] = {o.x, o.y, o.z}, dd[3] = {dl.x, dl.y, dl.z};
      // Slabs: the entry parameter is the largest of the axes' near planes, the exit the smallest far.
      LD enter = -1e30L, leave = 1e30L;
      int axis = 0;
      for (int i = 0; i < 3; ++i) {
        const LD t0 = (-hx[i] - oo[i]) / dd[i], t1 = (hx[i] - oo[i]) / dd[i];
        if (std::min(t0, t1) > enter) enter = std::min(t0, t1), axis = i;
        leave = std::min(leave, std::max(t0, t1));
      }
      const bool oracleHit = enter < leave && enter > 0;
      cpu::SurfaceHit hit;
      const bool cpuHit = cpu::traceNearest(far.prepared, eye, d, hit);
      // The hit's distance to the face's border, relative to the box: near an edge either answer stands.
      LD margin = 1e30L;
      for (int i = 0; i < 3; ++i)
        if (i != axis) margin = std::min(margin, hx[i] - std::abs(oo[i] + enter * dd[i]));
      const LD gap = std::abs(enter - leave) * std::sqrt(dot(dl, dl));
      if (std::abs(margin) < 1e-6L * LD(size) || gap < 1e-6L * LD(size)) continue;
      const LD cosTheta = std::abs(dd[axis]) / std::sqrt(dot(dl, dl));
      if (oracleHit && cosTheta < 0.3) continue;
      ++checked;
      if (oracleHit != cpuHit) {
        ++hitMissDisagreements;
        continue;
      }
      if (!oracleHit) continue;
      const double depthError = double(std::abs(LD(hit.t) - enter) / enter);
      worstDepth = std::max(worstDepth, depthError);
      if (!(depthError <= kTolerance)) ++depthDisagreements;
      // The face's normal in the world: the rotation's column `axis`, facing the camera.
      dvec3 n(rotation[axis][0], rotation[axis][1], rotation[axis][2]);
      if (glm::dot(n, d) > 0) n = -n;
      if (!(glm::length(glm::normalize(n) - hit.normal) <= 1e-12)) ++normalDisagreements;
    }
  }
  INFO("worst relative depth error " << worstDepth);
  CHECK(checked > 1500);
  CHECK(hitMissDisagreements == 0);
  CHECK(depthDisagreements == 0);
  CHECK(normalDisagreements == 0);
}

TEST_CASE("far from the origin: shadow rays decide a sphere's shadow edge as a long-double oracle does") {
  // The CPU reference's shadow ray leaves the hit as its ray's origin plus t d, each object's map
  // taking (o − b) + t d (cpu/trace.cpp occluded), as the GPU's camera-relative one does. From the
  // world hit point o + t d it carried that point's rounding, ~1e-16 of its distance from the
  // origin (1.9e-9 m at 1e7 m), and decided points of a plate that near a sphere's shadow edge on
  // the wrong side. Each sample aims a camera ray at a point of the plate whose ray to the lamp
  // passes the sphere at a signed gap δ (log-uniform 1e-12 to 1e-5 of the radius); the oracle
  // intersects the camera ray as it is in doubles with the plate and measures the gap again, in
  // long double relative to the plate's location (all differences of the scene's doubles are exact
  // there). Tolerance: the CPU's gap errs by a few roundings of the scene's size (2⁻⁵³ · ~10 r):
  // samples within 1e-12 r of the edge are left out, ~1000 times that.
  test::TempFolder dir;
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> unit(-1, 1);
  int checked = 0, disagreements = 0, wrongFirstHits = 0;
  for (int scene = 0; scene < 60; ++scene) {
    const double offset = scene < 6 ? 0.0 : std::pow(10.0, 1 + 6 * std::abs(unit(rng)));  // up to 1e7 m
    const double r = std::pow(10.0, -3 + 2 * std::abs(unit(rng)));                        // 1 mm to 0.1 m
    const dvec3 F = offset * glm::normalize(dvec3(unit(rng), unit(rng), unit(rng)));  // the plate's location
    // Relative to the plate (plane z = 0): the sphere 3 r above it, the lamp above the sphere, the
    // camera beside the lamp; each rounded to world doubles as the scene states it.
    const dvec3 S = F + dvec3(0, 0, 3 * r), L = F + r * dvec3(0.5 * unit(rng), 0.5 * unit(rng), 10);
    const dvec3 eye = F + r * dvec3(6 * unit(rng), 6 * unit(rng), 9);
    const std::string path = dir.write(
        "shadow.lua", kCamera + "plate = Object.Simple { shape = Shape.Plane { tileSize = {1, 1}; location = " + luaVector(F) +
                          " } }\nball = Object.Simple { shape = Shape.Sphere { radius = " + g17(r) + "; location = " +
                          luaVector(S) + " } }\n");
    const PreparedScene ps = prepareScene(loadScene(path, {}), {1});
    const auto rel = [&](dvec3 p) { return V3{LD(p.x) - LD(F.x), LD(p.y) - LD(F.y), LD(p.z) - LD(F.z)}; };  // exact
    const V3 s = rel(S), l = rel(L), o = rel(eye);
    const LD R = LD(r);
    // The gap between the sphere and the line through a and b: distance of S from it, minus r.
    const auto gap = [&](V3 a, V3 b) {
      const V3 u = sub(b, a), w = sub(s, a);
      const V3 c = {u.y * w.z - u.z * w.y, u.z * w.x - u.x * w.z, u.x * w.y - u.y * w.x};
      return std::sqrt(dot(c, c) / dot(u, u)) - R;
    };
    for (int k = 0; k < 60; ++k) {
      // A ray from the lamp passing the sphere at gap δ, met with the plate.
      const V3 a = sub(s, l);
      const LD D = std::sqrt(dot(a, a));
      const V3 e1 = {a.x / D, a.y / D, a.z / D};
      const LD phi = std::acos(LD(-1)) * LD(unit(rng));
      // e2: a unit vector normal to e1 at angle phi about it (e1 is nearly −z).
      V3 p = {std::cos(phi), std::sin(phi), 0};
      const LD pe = dot(p, e1);
      p = {p.x - pe * e1.x, p.y - pe * e1.y, p.z - pe * e1.z};
      const LD pn = std::sqrt(dot(p, p));
      const V3 e2 = {p.x / pn, p.y / pn, p.z / pn};
      const LD delta = std::copysign(R * std::pow(LD(10), -12 + 7 * LD(std::abs(unit(rng)))), LD(unit(rng)));
      const LD sinA = (R + delta) / D, cosA = std::sqrt(1 - sinA * sinA);
      const V3 u = {cosA * e1.x + sinA * e2.x, cosA * e1.y + sinA * e2.y, cosA * e1.z + sinA * e2.z};
      const LD lambda = -l.z / u.z;
      const V3 q = {l.x + lambda * u.x, l.y + lambda * u.y, 0};
      // The camera ray towards that point, its direction rounded to doubles as a small vector (through
      // a world target point it would round by ~1e-16 of the offset and miss the edge by as much).
      const V3 qo = sub(q, o);
      const dvec3 d(double(qo.x), double(qo.y), double(qo.z));
      const V3 dl = {LD(d.x), LD(d.y), LD(d.z)};
      // Where it really meets the plate, and the gap of that point's ray to the lamp.
      const LD t = -o.z / dl.z;
      const V3 hitPoint = {o.x + t * dl.x, o.y + t * dl.y, 0};
      const LD g = gap(hitPoint, l);
      if (std::abs(g) < 1e-12L * R) continue;
      if (gap(o, {o.x + dl.x, o.y + dl.y, o.z + dl.z}) < 1e-6L * R) continue;  // the camera sees the sphere there
      ++checked;
      cpu::SurfaceHit hit;
      if (!cpu::traceNearest(ps, eye, d, hit) || ps.objects[std::size_t(hit.object)].name != "plate") {
        ++wrongFirstHits;
        continue;
      }
      if (cpu::occluded(ps, hit, L) != (g < 0)) ++disagreements;
    }
  }
  CHECK(checked > 2500);  // of 3600: the rest where the camera's ray passes the sphere, or within 1e-12 r
  CHECK(wrongFirstHits == 0);
  CHECK(disagreements == 0);
}
