#include "texture/bspline.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace dicsynth {
namespace {

// The elimination of one line's banded system depends only on the line's length n, never on its
// values: it is factored once per length (LineSolver) and then applied to many lines at once. A
// column pass then runs row by row over a block of adjacent columns (contiguous memory) instead of
// walking each column with a stride of one image row, and rows and column blocks run on all
// cores. Every line gets exactly the operations, in the same order, of a one-line-at-a-time solve
// (same divisions, no reciprocals, no reassociation), so the coefficients are bit-identical to it.
//
// Cubic, rows of the tridiagonal system:
//   row 0:      (5/6) c0 + (1/6) c1 = f0                (c[−1] = c[0])
//   row k:      (1/6) c[k−1] + (4/6) c[k] + (1/6) c[k+1] = f[k]
//   row n−1:    (1/6) c[n−2] + (5/6) c[n−1] = f[n−1]    (c[n] = c[n−1])
// solved by the Thomas algorithm: diag[k] the pivots, upper[k] the modified super-diagonal.
// Quintic: Σ_{m=−2..2} b[m] c[mirror(k + m)] = f[k], b = {1, 26, 66, 26, 1}/120, by banded Gaussian
// elimination (half-bandwidth 2; mirrored indices of a row stay within 2 of k, so the band holds
// them): factor[2k + (r − k − 1)] eliminates row r with row k, band[5k + o + 2] is the reduced
// row k's entry in column k + o.
class LineSolver {
 public:
  LineSolver(std::size_t n, Interpolation kind) : n_(n), quintic_(kind == Interpolation::Quintic) {
    if (n_ == 1) return;  // the weights sum to 1: c0 = f0
    quintic_ ? factorQuintic() : factorCubic();
  }

  // Solves `count` lines in place: element k of line j is at f[k * stride + j * next] (a block of
  // columns: stride = W, next = 1; a block of rows: stride = 1, next = W). Lines are independent:
  // interleaving them keeps the divider and the memory busy (one line alone is a chain of dependent
  // divisions).
  void solve(double* f, std::size_t stride, std::size_t next, std::size_t count) const {
    if (n_ == 1) return;
    quintic_ ? solveQuintic(f, stride, next, count) : solveCubic(f, stride, next, count);
  }

 private:
  static constexpr double kOff = 1.0 / 6.0, kMid = 4.0 / 6.0, kEnd = 5.0 / 6.0;

  void factorCubic() {
    diag_.resize(n_);
    upper_.resize(n_);
    diag_[0] = kEnd;
    upper_[0] = kOff / diag_[0];
    for (std::size_t k = 1; k < n_; ++k) {
      diag_[k] = (k + 1 == n_ ? kEnd : kMid) - kOff * upper_[k - 1];
      upper_[k] = kOff / diag_[k];
    }
  }

  void solveCubic(double* f, std::size_t stride, std::size_t next, std::size_t count) const {
    for (std::size_t j = 0; j < count; ++j) f[j * next] /= diag_[0];
    for (std::size_t k = 1; k < n_; ++k) {
      double* row = f + k * stride;
      const double* prev = row - stride;
      const double d = diag_[k];
      for (std::size_t j = 0; j < count; ++j) row[j * next] = (row[j * next] - kOff * prev[j * next]) / d;
    }
    for (std::size_t k = n_ - 1; k-- > 0;) {
      double* row = f + k * stride;
      const double* after = row + stride;
      const double u = upper_[k];
      for (std::size_t j = 0; j < count; ++j) row[j * next] -= u * after[j * next];
    }
  }

  double& A(std::size_t r, std::size_t c) { return band_[5 * r + (c + 2 - r)]; }
  double A(std::size_t r, std::size_t c) const { return band_[5 * r + (c + 2 - r)]; }

  void factorQuintic() {
    const double b[5] = {1.0 / 120, 26.0 / 120, 66.0 / 120, 26.0 / 120, 1.0 / 120};
    band_.assign(5 * n_, 0.0);
    factor_.assign(2 * n_, 0.0);
    for (std::size_t k = 0; k < n_; ++k)
      for (int m = -2; m <= 2; ++m) A(k, std::size_t(mirrorIndex(int(k) + m, int(n_)))) += b[m + 2];
    for (std::size_t k = 0; k < n_; ++k) {
      const std::size_t last = std::min(k + 2, n_ - 1);
      for (std::size_t r = k + 1; r <= last; ++r) {
        const double factor = A(r, k) / A(k, k);
        for (std::size_t c = k; c <= last; ++c) A(r, c) -= factor * A(k, c);
        factor_[2 * k + (r - k - 1)] = factor;
      }
    }
  }

  void solveQuintic(double* f, std::size_t stride, std::size_t next, std::size_t count) const {
    for (std::size_t k = 0; k < n_; ++k) {
      const double* rowK = f + k * stride;
      const std::size_t last = std::min(k + 2, n_ - 1);
      for (std::size_t r = k + 1; r <= last; ++r) {
        double* row = f + r * stride;
        const double factor = factor_[2 * k + (r - k - 1)];
        for (std::size_t j = 0; j < count; ++j) row[j * next] -= factor * rowK[j * next];
      }
    }
    for (std::size_t k = n_; k-- > 0;) {
      double* row = f + k * stride;
      const std::size_t last = std::min(k + 2, n_ - 1);
      const double pivot = A(k, k);
      for (std::size_t j = 0; j < count; ++j) {
        double rest = row[j * next];
        for (std::size_t c = k + 1; c <= last; ++c) rest -= A(k, c) * f[c * stride + j * next];
        row[j * next] = rest / pivot;
      }
    }
  }

  std::size_t n_;
  bool quintic_;
  std::vector<double> diag_, upper_;   // cubic
  std::vector<double> band_, factor_;  // quintic
};

// A line that repeats (c[k + n] = c[k]): the circulant system Σ_m b[m] c[(k + m) mod n] = f[k] with
// the b above, solved by the B-spline's recursive filter (Unser, Aldroubi and Eden 1993). The
// symbol B(z) = Σ b[m] z^m factors as λ⁻¹ Π_z (1 − z ζ⁻¹)(1 − z ζ) over the poles z (|z| < 1), so
// c = λ f followed, per pole, by a causal pass c⁺[k] = c[k] + z c⁺[k−1] and an anticausal one
// c[k] = z (c[k+1] − c⁺[k]). λ = Π (1 − z)(1 − 1/z) = Π (2 − w) with w = z + 1/z the roots of
// B's symmetric form: cubic w = −4, λ = 6; quintic w = −13 ± √105, λ = (15 − √105)(15 + √105) =
// 120. On a periodic line the recursions' starts are their infinite sums folded over the period
// (exact, no truncation):
//   c⁺[0]   = Σ_{j=0}^{n−1} z^j c[(n − j) mod n] / (1 − z^n)      (c⁺[k] = Σ_{j≥0} z^j c[k − j])
//   c[n−1]  = −z Σ_{j=0}^{n−1} z^j c⁺[(n − 1 + j) mod n] / (1 − z^n)   (c[k] = −z Σ_{j≥0} z^j c⁺[k + j])
// Each pass is a contraction (|z| < 1), so the solve is accurate to a few ulps: tests/texture/
// test_bspline.cpp compares it with a dense Gaussian elimination of the circulant system.
class PeriodicLineSolver {
 public:
  PeriodicLineSolver(std::size_t n, Interpolation kind) : n_(n) {
    // z = 2 / (w − √(w² − 4)): the root of z + 1/z = w inside the unit circle, without cancellation.
    const auto pole = [](double w) { return 2.0 / (w - std::sqrt(w * w - 4.0)); };
    if (kind == Interpolation::Quintic) {
      poles_ = {pole(-13.0 + std::sqrt(105.0)), pole(-13.0 - std::sqrt(105.0))};
      gain_ = 120.0;
    } else {
      poles_ = {pole(-4.0)};  // √3 − 2
      gain_ = 6.0;
    }
  }

  void solve(double* f, std::size_t stride, std::size_t next, std::size_t count) const {
    std::vector<double> c(n_);
    for (std::size_t j = 0; j < count; ++j) {
      double* line = f + j * next;
      for (std::size_t k = 0; k < n_; ++k) c[k] = gain_ * line[k * stride];
      for (const double z : poles_) {
        double zj = 1, sum = 0;
        for (std::size_t i = 0; i < n_; ++i, zj *= z) sum += zj * c[(n_ - i) % n_];
        const double period = 1.0 - zj;  // zj = z^n here
        c[0] = sum / period;
        for (std::size_t k = 1; k < n_; ++k) c[k] += z * c[k - 1];
        zj = 1;
        sum = 0;
        for (std::size_t i = 0; i < n_; ++i, zj *= z) sum += zj * c[(n_ - 1 + i) % n_];
        c[n_ - 1] = -z * sum / period;
        for (std::size_t k = n_ - 1; k-- > 0;) c[k] = z * (c[k + 1] - c[k]);
      }
      for (std::size_t k = 0; k < n_; ++k) line[k * stride] = c[k];
    }
  }

 private:
  std::size_t n_;
  std::vector<double> poles_;
  double gain_;
};

// One axis's solve: mirrored borders (LineSolver) or periodic ones (PeriodicLineSolver).
void solveLines(std::size_t n, Interpolation kind, bool periodic, std::vector<double>& values,
                std::size_t lines, std::size_t stride, std::size_t next, std::size_t lineStep) {
  constexpr std::size_t kBlock = 8;
  const auto run = [&](const auto& solver) {
    parallelFor((lines + kBlock - 1) / kBlock, [&](std::size_t block) {
      const std::size_t first = block * kBlock;
      solver.solve(values.data() + first * lineStep, stride, next, std::min(kBlock, lines - first));
    });
  };
  if (periodic)
    run(PeriodicLineSolver(n, kind));
  else
    run(LineSolver(n, kind));
}

}  // namespace

void bsplinePrefilter(std::vector<double>& values, int width, int height, Interpolation kind, TextureWrap wrap) {
  DS_CHECK(width > 0 && height > 0 && values.size() == std::size_t(width) * std::size_t(height),
           "texture size mismatch");
  const std::size_t w = std::size_t(width), h = std::size_t(height);
  // Blocks of 8 lines solved together: 8 rows walked in step (element stride 1, next line w), or 8
  // adjacent columns walked row by row (stride w, next 1: 64 bytes per row of the block, whole
  // cache lines).
  solveLines(w, kind, repeatsU(wrap), values, h, 1, w, w);
  solveLines(h, kind, repeatsV(wrap), values, w, w, 1, 1);
}

}  // namespace dicsynth
