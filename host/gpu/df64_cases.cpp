// The df64 self-test's inputs and their reference values.
//
// Reference: long double (64-bit significand on x86-64 Linux, 113 bits on AArch64 Linux). Every
// input hi + lo is built to span at most 64 bits (lo at most 16 binades below hi's last bit, or a
// split double), so it is exact in long double; each reference is then one correctly rounded
// operation (+, −, ×, /, sqrt: relative error ≤ 2^-64), or for dot and cross a few of them, whose
// error ≤ 4·2^-64 Σ|aᵢbᵢ| is measured on the same normwise scale. Against the 2^-44 bound under
// test that uncertainty is 2^-20 of the bound: no exact rational arithmetic is needed.
//
// Range: df64 keeps ~48 bits only for magnitudes in [2^-72, 2^114] (shaders/lib/df64.glsl), so
// every operand and every result lies there or is zero; "results near the limits" are results
// near these ends. Random numbers come from ds_hash of a counter (shared/rng.h): the same inputs on
// every platform and compiler.
#include "gpu/df64_cases.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

#include "core/error.h"
#include "shared/rng.h"

namespace dicsynth::gpu::df64 {

namespace {

using LD = long double;
static_assert(std::numeric_limits<LD>::digits >= 64, "the df64 reference needs a 64-bit long double");

constexpr LD kMinMagnitude = 0x1p-72L, kMaxMagnitude = 0x1p114L;
constexpr double kU2 = 0x1p-48;  // u² with u = 2^-24: the unit of the documented bounds

struct OpInfo {
  int op;
  const char* name;
  double boundU2;  // documented bound, in u² (df64.glsl)
  int minWidth, maxWidth;
};
constexpr OpInfo kOps[] = {
    {DS_DF64_OP_ADD, "add", 3, 1, 4},
    {DS_DF64_OP_SUB, "sub", 3, 1, 4},
    {DS_DF64_OP_MUL, "mul", 8, 1, 4},
    {DS_DF64_OP_DIV, "div", 12, 1, 4},
    {DS_DF64_OP_SQRT, "sqrt", 5.125, 1, 4},  // div and sqrt: boundU2() below
    {DS_DF64_OP_ADD_FLOAT, "add_float", 2, 1, 4},
    {DS_DF64_OP_MUL_FLOAT, "mul_float", 3, 1, 4},
    {DS_DF64_OP_ADD_SCALAR, "add_scalar", 3, 1, 4},
    {DS_DF64_OP_SUB_SCALAR, "sub_scalar", 3, 1, 4},
    {DS_DF64_OP_MUL_SCALAR, "mul_scalar", 8, 1, 4},
    {DS_DF64_OP_DIV_SCALAR, "div_scalar", 12, 1, 4},
    {DS_DF64_OP_MUL_SCALAR_FLOAT, "mul_scalar_float", 3, 1, 4},
    {DS_DF64_OP_NEG, "neg", 0, 1, 4},
    {DS_DF64_OP_ABS, "abs", 0, 1, 4},
    {DS_DF64_OP_DOT, "dot", 17, 3, 4},
    {DS_DF64_OP_CROSS, "cross", 11, 3, 3},
    {DS_DF64_OP_FLOOR, "floor", 0, 1, 1},
    {DS_DF64_OP_COMPARE, "compare", 0, 1, 1},
    {DS_DF64_OP_CONSTANTS, "constants", 1, 1, 1},
};

bool isScalarB(int op) {
  return op == DS_DF64_OP_ADD_SCALAR || op == DS_DF64_OP_SUB_SCALAR || op == DS_DF64_OP_MUL_SCALAR ||
         op == DS_DF64_OP_DIV_SCALAR || op == DS_DF64_OP_MUL_SCALAR_FLOAT;
}
bool isFloatB(int op) {
  return op == DS_DF64_OP_ADD_FLOAT || op == DS_DF64_OP_MUL_FLOAT || op == DS_DF64_OP_MUL_SCALAR_FLOAT;
}

struct Num {
  float hi = 0.0f, lo = 0.0f;
};
LD value(Num n) { return LD(n.hi) + LD(n.lo); }
Num num(double x) {
  const Df64 d = splitDf64(x);
  return {d.hi, d.lo};
}
Num neg(Num n) { return {-n.hi, -n.lo}; }
// Normalized: hi is the float nearest to hi + lo (|lo| ≤ ulp(hi)/2, ties as float rounds them).
bool normalized(float hi, float lo) { return float(hi + lo) == hi; }
bool inDomain(LD x) {
  x = std::fabs(x);
  return x == 0 || (x >= kMinMagnitude && x <= kMaxMagnitude);
}

// Deterministic on every platform: ds_hash of (stream, counter).
class CaseRng {
 public:
  explicit CaseRng(std::uint32_t stream) : key_(ds_hash(stream * 0x9e3779b9u + 0x632be5abu)) {}
  std::uint32_t next() { return ds_hash_combine(key_, counter_++); }
  std::uint32_t below(std::uint32_t n) { return next() % n; }
  int range(int lo, int hi) { return lo + int(below(std::uint32_t(hi - lo + 1))); }
  bool coin() { return (next() & 1u) != 0; }
  double sign() { return coin() ? -1.0 : 1.0; }

 private:
  std::uint32_t key_, counter_ = 0;
};

// Every draw below is a statement of its own: C++ leaves the order of the operands and arguments of
// one expression to the compiler, and the inputs are to be the same on every platform. (Where
// draws once shared an expression, the statements keep GCC 12's order: the inputs are unchanged.)

// A float of random sign, binary exponent in [eMin, eMax] and 24-bit mantissa.
float randomFloat(CaseRng& r, int eMin, int eMax) {
  const float sign = float(r.sign());
  const int exponent = r.range(eMin, eMax);
  const float mantissa = 1.0f + float(r.next() >> 9) * 0x1p-23f;
  return sign * std::ldexp(mantissa, exponent);
}

// A lo with 24 random bits, k ≥ 1 binades below half an ulp of hi: |lo| < ulp(hi)/2.
float randomLo(CaseRng& r, float hi, int k) {
  if (hi == 0.0f) return 0.0f;
  const float m = 1.0f + float(r.next() >> 9) * 0x1p-23f;
  return float(r.sign()) * std::ldexp(m, std::ilogb(hi) - 24 - k);
}

// A random number of binary exponent in [eMin, eMax]: a split 53-bit double (most), a plain float,
// a lo far below hi's last bit (hi + lo spans up to 64 bits), or a lo of exactly half an ulp.
Num randomNum(CaseRng& r, int eMin, int eMax) {
  const double high = double(r.next() >> 6) * 0x1p-26;
  const double low = double(r.next() >> 6) * 0x1p-52;
  const double m = 1.0 + high + low;
  const double sign = r.sign();
  const int exponent = r.range(eMin, eMax);
  Num n = num(sign * std::ldexp(m, exponent));
  switch (r.below(8)) {
    case 0: n.lo = 0.0f; break;
    case 1: n.lo = randomLo(r, n.hi, r.range(2, 16)); break;
    case 2: {
      const float half = float(r.sign()) * std::ldexp(1.0f, std::ilogb(n.hi) - 24);
      if (normalized(n.hi, half)) n.lo = half;  // a tie that rounds to hi (hi even)
      break;
    }
    default: break;
  }
  return n;
}

// A number close to s·a (s = ±1), the other operand of a cancelling sum: exactly s·a, the same hi
// with another lo, hi one ulp away, or s·a·(1 ± 2^-k) for k in 1..50.
Num partner(CaseRng& r, Num a, float s) {
  Num b{s * a.hi, s * a.lo};
  switch (r.below(4)) {
    case 0: break;
    case 1: b.lo = randomLo(r, b.hi, r.range(1, 16)); break;
    case 2:
      b.hi = std::nextafter(b.hi, r.coin() ? INFINITY : -INFINITY);
      b.lo = randomLo(r, b.hi, r.range(1, 16));
      break;
    default: {
      const double sign = r.sign();
      const int k = r.range(1, 50);
      const double d = sign * std::ldexp(1.0 + double(r.next() >> 8) * 0x1p-24, -k);
      b = num((double(b.hi) + double(b.lo)) * (1.0 + d));
    }
  }
  if (!normalized(b.hi, b.lo)) b.lo = 0.0f;
  return b;
}

// The exact result of a component-wise operation (b: the operand the probe uses for it).
LD reference(int op, LD a, LD b) {
  switch (op) {
    case DS_DF64_OP_ADD: case DS_DF64_OP_ADD_FLOAT: case DS_DF64_OP_ADD_SCALAR: return a + b;
    case DS_DF64_OP_SUB: case DS_DF64_OP_SUB_SCALAR: return a - b;
    case DS_DF64_OP_MUL: case DS_DF64_OP_MUL_FLOAT: case DS_DF64_OP_MUL_SCALAR:
    case DS_DF64_OP_MUL_SCALAR_FLOAT: return a * b;
    case DS_DF64_OP_DIV: case DS_DF64_OP_DIV_SCALAR: return a / b;
    case DS_DF64_OP_SQRT: return std::sqrt(a);
    case DS_DF64_OP_NEG: return -a;
    case DS_DF64_OP_ABS: return std::fabs(a);
    case DS_DF64_OP_FLOOR: return std::floor(a);
  }
  return 0;
}

// One lane (a, b) of a component-wise operation. fixedB: the scalar b shared by all lanes.
std::pair<Num, Num> randomLane(int op, CaseRng& r, const Num* fixedB) {
  Num a, b;
  switch (op) {
    case DS_DF64_OP_ADD: case DS_DF64_OP_SUB: case DS_DF64_OP_ADD_FLOAT:
    case DS_DF64_OP_ADD_SCALAR: case DS_DF64_OP_SUB_SCALAR: {
      const float s = (op == DS_DF64_OP_SUB || op == DS_DF64_OP_SUB_SCALAR) ? 1.0f : -1.0f;
      if (fixedB) {
        b = *fixedB;
        a = r.coin() ? partner(r, b, s) : randomNum(r, -30, 40);
      } else {
        a = randomNum(r, -8, 40);
        const int e = std::ilogb(a.hi);
        switch (r.below(3)) {
          case 0: b = randomNum(r, -30, 40); break;
          case 1: b = randomNum(r, e - 3, e + 3); break;
          default: b = partner(r, a, s);
        }
      }
      break;
    }
    case DS_DF64_OP_MUL: case DS_DF64_OP_MUL_FLOAT: case DS_DF64_OP_MUL_SCALAR:
    case DS_DF64_OP_MUL_SCALAR_FLOAT: case DS_DF64_OP_DIV: case DS_DF64_OP_DIV_SCALAR:
      a = randomNum(r, -35, 35);
      b = fixedB ? *fixedB : randomNum(r, -35, 35);
      break;
    case DS_DF64_OP_SQRT: {
      const Num x = randomNum(r, -72, 113);
      a = x.hi < 0 ? neg(x) : x;
      break;
    }
    case DS_DF64_OP_NEG: case DS_DF64_OP_ABS: a = randomNum(r, -72, 113); break;
    case DS_DF64_OP_FLOOR:
      switch (r.below(3)) {
        case 0: a = randomNum(r, -3, 30); break;
        case 1:  // an integer hi: lo decides
          a.hi = float(int(r.next() >> 9) - (1 << 22));
          a.lo = randomLo(r, a.hi, r.range(1, 16));
          break;
        default: a = randomNum(r, 23, 40);  // hi an integer, lo may carry a fraction
      }
      break;
    case DS_DF64_OP_COMPARE:
      a = randomNum(r, -20, 20);
      switch (r.below(5)) {
        case 0: b = randomNum(r, -20, 20); break;
        case 1: b = a; break;
        case 2: b = {a.hi, randomLo(r, a.hi, r.range(1, 16))}; break;
        case 3: b = {std::nextafter(a.hi, r.coin() ? INFINITY : -INFINITY), 0.0f}; break;
        default: b = neg(a);
      }
      break;
  }
  if (isFloatB(op)) b.lo = 0.0f;
  return {a, b};
}

Df64ProbeItem makeItem(int op, int width) {
  Df64ProbeItem item{};
  item.op = std::uint32_t(op);
  item.width = std::uint32_t(width);
  return item;
}
void setA(Df64ProbeItem& item, int k, Num n) { item.aHi[k] = n.hi, item.aLo[k] = n.lo; }
void setB(Df64ProbeItem& item, int k, Num n) { item.bHi[k] = n.hi, item.bLo[k] = n.lo; }
Num getA(const Df64ProbeItem& item, int k) { return {item.aHi[k], item.aLo[k]}; }
Num getB(const Df64ProbeItem& item, int k) { return {item.bHi[k], item.bLo[k]}; }

// The operand b the probe uses in component k (scalar forms: component 0; float forms: hi only).
LD operandB(const Df64ProbeItem& item, int k) {
  const int op = int(item.op);
  const Num b = getB(item, isScalarB(op) ? 0 : k);
  return isFloatB(op) ? LD(b.hi) : value(b);
}

// Exact dot product and its scale Σ|aᵢbᵢ| (see the file comment on their accuracy).
std::pair<LD, LD> dotRef(const Df64ProbeItem& item) {
  LD sum = 0, scale = 0;
  for (int k = 0; k < int(item.width); ++k) {
    const LD p = value(getA(item, k)) * value(getB(item, k));
    sum += p;
    scale += std::fabs(p);
  }
  return {sum, scale};
}
std::pair<LD, LD> crossRef(const Df64ProbeItem& item, int k) {
  const int j = (k + 1) % 3, l = (k + 2) % 3;
  const LD p = value(getA(item, j)) * value(getB(item, l)), q = value(getA(item, l)) * value(getB(item, j));
  return {p - q, std::fabs(p) + std::fabs(q)};
}

// Every operand and exact result inside df64's range (dot, cross: their Σ|aᵢbᵢ|).
bool itemInDomain(const Df64ProbeItem& item) {
  const int op = int(item.op), w = int(item.width);
  for (int k = 0; k < w; ++k) {
    if (!inDomain(value(getA(item, k))) || !inDomain(value(getB(item, k)))) return false;
    if (!normalized(item.aHi[k], item.aLo[k]) || !normalized(item.bHi[k], item.bLo[k])) return false;
  }
  if (op == DS_DF64_OP_DOT) return inDomain(dotRef(item).second);
  if (op == DS_DF64_OP_CROSS) {
    for (int k = 0; k < 3; ++k)
      if (!inDomain(crossRef(item, k).second)) return false;
    return true;
  }
  if (op == DS_DF64_OP_COMPARE || op == DS_DF64_OP_FLOOR) return true;
  for (int k = 0; k < w; ++k)
    if (!inDomain(reference(op, value(getA(item, k)), operandB(item, k)))) return false;
  return true;
}

Df64ProbeItem randomVectorItem(int op, int width, CaseRng& r) {
  Df64ProbeItem item = makeItem(op, width);
  const bool cancel = r.below(3) == 0;
  const int e = cancel ? 20 : 30;
  for (int k = 0; k < width; ++k) {
    setA(item, k, randomNum(r, -e, e));
    setB(item, k, randomNum(r, -e, e));
  }
  if (cancel && op == DS_DF64_OP_DOT) {
    // The last b makes the dot product cancel to ~2^-53 of Σ|aᵢbᵢ| (or exactly).
    auto a = [&](int k) { return joinDf64({item.aHi[k], item.aLo[k]}); };
    double s = 0;
    for (int k = 0; k + 1 < width; ++k) s += a(k) * joinDf64({item.bHi[k], item.bLo[k]});
    setB(item, width - 1, num(-s / a(width - 1)));
  } else if (cancel) {
    // b nearly parallel to a: every cross component cancels.
    const double cSign = r.sign();
    const double c = cSign * std::ldexp(1.0, r.range(-10, 10));
    for (int k = 0; k < 3; ++k) {
      const double dSign = r.sign();
      const double d = dSign * std::ldexp(1.0, -r.range(1, 50));
      setB(item, k, num(joinDf64({item.aHi[k], item.aLo[k]}) * c * (1.0 + d)));
    }
  }
  return item;
}

Df64ProbeItem randomItem(int op, int width, CaseRng& r) {
  if (op == DS_DF64_OP_DOT || op == DS_DF64_OP_CROSS) return randomVectorItem(op, width, r);
  Df64ProbeItem item = makeItem(op, width);
  Num b0;
  for (int k = 0; k < width; ++k) {
    const auto [a, b] = randomLane(op, r, isScalarB(op) && k > 0 ? &b0 : nullptr);
    if (k == 0) b0 = b;
    setA(item, k, a);
    setB(item, k, isScalarB(op) ? b0 : b);
  }
  return item;
}

// ---- Hard cases (width 1) ----
const Num kZero{0.0f, 0.0f}, kNegZero{-0.0f, 0.0f}, kOne{1.0f, 0.0f};
const Num kTieUp{1.0f, 0x1p-24f};     // lo = ulp(1)/2: a tie, rounded to the even hi = 1
const Num kTieDown{1.0f, -0x1p-25f};  // the tie below 1 (ulp there is 2^-24)
const Num kMaxMant{0x1.fffffep0f, 0x1.fffffep-25f};  // all ones, lo just below half an ulp
const Num kP12{1.0f + 0x1p-12f, 0.0f};               // (1 + 2^-12)²: the product is a tie in float

std::vector<std::pair<Num, Num>> addCases() {
  std::vector<std::pair<Num, Num>> c;
  const Num third = num(1.0 / 3), pi = num(M_PI), big = num(0x1.8p113), tiny = num(0x1.4p-72);
  for (Num x : {kOne, third, pi, big, tiny, kMaxMant, kTieUp})
    c.insert(c.end(), {{x, kZero}, {kZero, x}, {x, neg(x)}, {neg(x), kNegZero}});
  c.insert(c.end(), {{kZero, kZero}, {kNegZero, kZero}, {kNegZero, kNegZero},
                     {kOne, {-1.0f, 0x1p-30f}}, {kTieUp, kTieUp}, {kTieUp, kTieDown},
                     {kMaxMant, {0x1p-24f, 0.0f}}, {kMaxMant, kMaxMant}, {kMaxMant, neg(kOne)},
                     {big, num(0x1.333333p111)}, {num(0x1.ffffffffffp113), neg(big)},
                     {num(0x1.8p-70), num(-0x1.333333p-70)}, {{0x1p-72f, 0.0f}, {0x1p-72f, 0.0f}},
                     {third, num(2.0 / 3)}, {{1.0f, 0x1p-40f}, {-1.0f, 0.0f}}});
  for (int k : {-36, 0, 1, 30})
    for (int j : {-36, -1, 0, 30})
      c.insert(c.end(), {{num(std::ldexp(1, k)), num(std::ldexp(1, j))},
                         {num(std::ldexp(1, k)), num(-std::ldexp(1, j))}});
  return c;
}

std::vector<std::pair<Num, Num>> mulCases() {
  const Num third = num(1.0 / 3), pi = num(M_PI), sqrt2 = num(M_SQRT2);
  std::vector<std::pair<Num, Num>> c = {
      {kP12, kP12}, {kTieUp, kTieUp}, {kTieDown, kTieUp}, {kMaxMant, kMaxMant}, {third, num(3)},
      {sqrt2, sqrt2}, {num(0x1.8p56), num(0x1p57)}, {num(0x1.fffffffp56), num(0x1.fffffffp56)},
      {num(0x1p-36), num(0x1p-36)}, {kZero, pi}, {pi, kZero}, {kNegZero, pi}, {pi, neg(pi)},
      {kOne, num(0x1.8p113)}, {num(0x1p-72), kOne}};
  for (int k : {-35, -1, 0, 1, 35})
    for (int j : {-35, 0, 35}) c.push_back({num(std::ldexp(1, k)), num(-std::ldexp(1, j))});
  return c;
}

std::vector<std::pair<Num, Num>> divCases() {
  const Num third = num(1.0 / 3), pi = num(M_PI), big = num(0x1.8p113);
  std::vector<std::pair<Num, Num>> c = {
      {pi, pi}, {kOne, num(3)}, {num(2), num(3)}, {kOne, third}, {num(0x1p-36), num(0x1p36)},
      {num(0x1.8p56), num(0x1p-57)}, {kZero, pi}, {kNegZero, pi}, {kTieUp, kP12}, {kMaxMant, kTieUp},
      {kOne, kMaxMant}, {big, big}, {{0x1p-72f, 0.0f}, {0x1p-72f, 0.0f}}, {kOne, num(-7)},
      {kTieDown, kTieUp}, {num(1e-10), num(3e10)}};
  for (int k : {-35, -1, 0, 1, 35})
    for (int j : {-35, 0, 35}) c.push_back({num(std::ldexp(1, k)), num(-std::ldexp(1, j))});
  return c;
}

std::vector<Num> sqrtCases() {
  std::vector<Num> c = {kZero, kNegZero, num(4), num(2), {0x1p-72f, 0.0f}, num(0x1.8p113),
                        num(0x1.ffffffffffp113), kTieUp, kTieDown, kMaxMant, num(0x1p113),
                        num(0x1.8p-71), num(1.0 / 3), kP12};
  for (int k : {-72, -71, -1, 0, 1, 57, 112, 113}) c.push_back(num(std::ldexp(1, k)));
  return c;
}

std::vector<Num> floorCases() {
  return {{1.0f, -0x1p-30f}, {1.0f, 0x1p-30f}, {-1.0f, 0x1p-30f}, {-1.0f, -0x1p-30f},
          {0x1p24f, -0.5f}, {0x1p30f, 17.5f}, {0x1p30f, -17.5f}, {0.5f, 0.0f}, {-0.5f, 0.0f},
          kZero, kNegZero, {8388607.5f, 0.0f}, {-8388607.5f, 0.0f}, {3.0f, -0x1p-30f}, kMaxMant};
}

std::vector<std::pair<Num, Num>> compareCases() {
  const Num pi = num(M_PI), a{1.0f, 0x1p-30f}, b{1.0f, -0x1p-30f};
  return {{kOne, kOne}, {kOne, kTieUp}, {kTieUp, kOne}, {kZero, kNegZero}, {kNegZero, kZero},
          {kOne, neg(kOne)}, {a, b}, {b, a}, {pi, pi}, {neg(pi), neg(pi)}, {neg(a), neg(b)},
          {neg(b), neg(a)}, {kZero, {0x1p-72f, 0.0f}}};
}

void addHardCases(std::vector<Df64ProbeItem>& items, int op) {
  auto pairItem = [&](Num a, Num b) {
    Df64ProbeItem item = makeItem(op, 1);
    if (isFloatB(op)) b.lo = 0.0f;
    setA(item, 0, a);
    setB(item, 0, b);
    DS_CHECK(op == DS_DF64_OP_COMPARE || itemInDomain(item),
             "df64 hard case of op " + std::to_string(op) + " outside df64's range: a = (" +
                 std::to_string(a.hi) + ", " + std::to_string(a.lo) + "), b = (" + std::to_string(b.hi) +
                 ", " + std::to_string(b.lo) + ")");
    items.push_back(item);
  };
  switch (op) {
    case DS_DF64_OP_ADD: case DS_DF64_OP_SUB: case DS_DF64_OP_ADD_FLOAT:
    case DS_DF64_OP_ADD_SCALAR: case DS_DF64_OP_SUB_SCALAR:
      // a − b with the sums' b negated: the same cancellations and range ends.
      for (auto [a, b] : addCases())
        pairItem(a, op == DS_DF64_OP_SUB || op == DS_DF64_OP_SUB_SCALAR ? neg(b) : b);
      break;
    case DS_DF64_OP_MUL: case DS_DF64_OP_MUL_FLOAT: case DS_DF64_OP_MUL_SCALAR:
    case DS_DF64_OP_MUL_SCALAR_FLOAT:
      for (auto [a, b] : mulCases()) pairItem(a, b);
      break;
    case DS_DF64_OP_DIV: case DS_DF64_OP_DIV_SCALAR:
      for (auto [a, b] : divCases()) pairItem(a, b);
      break;
    case DS_DF64_OP_SQRT:
      for (Num a : sqrtCases()) pairItem(a, kZero);
      break;
    case DS_DF64_OP_NEG: case DS_DF64_OP_ABS:
      for (Num a : {kZero, kNegZero, num(M_PI), num(-M_PI), Num{-1.0f, 0x1p-30f}, Num{1.0f, -0x1p-30f},
                    num(0x1.8p113), num(-0x1p-72), kMaxMant})
        pairItem(a, kZero);
      break;
    case DS_DF64_OP_FLOOR:
      for (Num a : floorCases()) pairItem(a, kZero);
      break;
    case DS_DF64_OP_COMPARE:
      for (auto [a, b] : compareCases()) pairItem(a, b);
      break;
    case DS_DF64_OP_CONSTANTS: items.push_back(makeItem(op, 1)); break;
    default: break;  // dot, cross: the random set's cancelling vectors are their hard cases
  }
}

// The documented bound of an operation in u² (shaders/lib/df64.glsl), with the device's float
// division (δ u) and sqrt (σ u) errors where df_div and df_sqrt use them; δ = σ = 1 gives the
// table's numbers (the first-order analyses of df64.glsl, plus 1u² of margin for sqrt):
//   div   (2 + δ)² + 3:  q1 = fl(a.hi / b.hi) is off by (2 + δ)u (a.lo, b.lo, the division); q2
//         corrects it from r = a − q1·b (3u² in df), itself off by (2 + δ)u of its size ε|a/b|.
//   sqrt  ε²/2 + (1 + δ)ε + 1 with ε = σ + 1/2: y = fl(sqrt(a.hi)) is off by εu (a.lo, the sqrt);
//         Newton leaves ε²/2; its correction c = r.hi / 2y (|c| ≈ ε|y|) is off by (1 + δ)u.
double boundU2(const OpInfo& info, const FloatAccuracy& f) {
  switch (info.op) {
    case DS_DF64_OP_DIV: case DS_DF64_OP_DIV_SCALAR: return (2 + f.divU) * (2 + f.divU) + 3;
    case DS_DF64_OP_SQRT: {
      const double e = f.sqrtU + 0.5;
      return e * e / 2 + (1 + f.divU) * e + 1;
    }
    default: return info.boundU2;
  }
}

// Relative error of got against ref; a wrong zero, a NaN or an infinity counts as 1 (100 %).
double relError(LD got, LD ref, LD scale) {
  if (std::isnan(got) || std::isinf(got)) return 1.0;
  if (scale == 0) return got == 0 ? 0.0 : 1.0;
  return double(std::fabs(got - ref) / scale);
}

}  // namespace

std::vector<Df64ProbeItem> makeItems(std::size_t randomInputsPerOp) {
  std::vector<Df64ProbeItem> items;
  // The float division and sqrt (FloatAccuracy): random mantissas over the exponents df64 uses,
  // four components per item.
  for (int op : {DS_DF64_OP_FLOAT_DIV, DS_DF64_OP_FLOAT_SQRT}) {
    CaseRng r(std::uint32_t(op) + 1u);
    for (std::size_t i = 0; i < randomInputsPerOp; i += 4) {
      Df64ProbeItem item = makeItem(op, 4);
      for (int k = 0; k < 4; ++k) {
        item.aHi[k] = randomFloat(r, -60, 60);
        if (op == DS_DF64_OP_FLOAT_SQRT) item.aHi[k] = std::fabs(item.aHi[k]);
        item.bHi[k] = randomFloat(r, -50, 50);
      }
      items.push_back(item);
    }
  }
  for (const OpInfo& info : kOps) {
    addHardCases(items, info.op);
    if (info.op == DS_DF64_OP_CONSTANTS) continue;
    CaseRng r(std::uint32_t(info.op) + 1u);
    std::size_t inputs = 0;
    for (int i = 0; inputs < randomInputsPerOp; ++i) {
      const int width = info.minWidth + i % (info.maxWidth - info.minWidth + 1);
      Df64ProbeItem item = randomItem(info.op, width, r);
      while (!itemInDomain(item)) item = randomItem(info.op, width, r);
      items.push_back(item);
      inputs += info.op == DS_DF64_OP_DOT ? 1 : std::size_t(width);  // results checked
    }
  }
  return items;
}

FloatAccuracy floatAccuracy(std::span<const Df64ProbeItem> items, std::span<const Df64ProbeResult> results) {
  DS_CHECK(items.size() == results.size(), "one df64 probe result per item");
  FloatAccuracy f;
  double div = 0, sqrt = 0;
  bool anyDiv = false, anySqrt = false;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const int op = int(items[i].op);
    if (op != DS_DF64_OP_FLOAT_DIV && op != DS_DF64_OP_FLOAT_SQRT) continue;
    for (int k = 0; k < int(items[i].width); ++k) {
      const LD a = items[i].aHi[k], b = items[i].bHi[k];
      const LD ref = op == DS_DF64_OP_FLOAT_DIV ? a / b : std::sqrt(a);
      const double err = relError(LD(results[i].hi[k]), ref, std::fabs(ref)) / 0x1p-24;
      if (op == DS_DF64_OP_FLOAT_DIV) div = std::max(div, err), anyDiv = true;
      else sqrt = std::max(sqrt, err), anySqrt = true;
    }
  }
  // Never below correct rounding's 1 (the analysis needs no less), never above what Vulkan allows
  // a float division (2.5 ulp, ≤ 5u) and sqrt (inherited from 1/inversesqrt: 2 + 2.5 ulp, ≤ 9u):
  // a device outside the specification fails the bounds instead of loosening them.
  if (anyDiv) f.divU = std::clamp(div, 1.0, 5.0);
  if (anySqrt) f.sqrtU = std::clamp(sqrt, 1.0, 9.0);
  return f;
}

std::vector<Df64OpError> evaluate(std::span<const Df64ProbeItem> items,
                                  std::span<const Df64ProbeResult> results) {
  DS_CHECK(items.size() == results.size(), "one df64 probe result per item");
  std::vector<Df64OpError> errors;
  std::vector<int> slot(DS_DF64_OP_COUNT, -1);
  const FloatAccuracy f = floatAccuracy(items, results);
  for (const OpInfo& info : kOps) {
    slot[std::size_t(info.op)] = int(errors.size());
    Df64OpError e;
    e.name = info.name;
    e.bound = boundU2(info, f) * kU2;
    errors.push_back(e);
  }
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Df64ProbeItem& item = items[i];
    const Df64ProbeResult& res = results[i];
    const int op = int(item.op), w = int(item.width);
    if (op >= DS_DF64_OP_COUNT || slot[std::size_t(op)] < 0) continue;
    Df64OpError& e = errors[std::size_t(slot[std::size_t(op)])];
    auto record = [&](int k, double err) {
      e.maxRelError = std::max(e.maxRelError, err);
      e.unnormalized += normalized(res.hi[k], res.lo[k]) ? 0 : 1;
      e.inputs += 1;
    };
    auto got = [&](int k) { return LD(res.hi[k]) + LD(res.lo[k]); };
    if (op == DS_DF64_OP_COMPARE) {
      const LD a = value(getA(item, 0)), b = value(getB(item, 0));
      const bool ok = (res.hi[0] == 1.0f) == (a < b) && (res.hi[1] == 1.0f) == (a <= b) &&
                      (res.hi[2] == 1.0f) == (a > b) && (res.hi[3] == 1.0f) == (a >= b) &&
                      (res.lo[0] == 1.0f) == (a == b);
      e.maxRelError = std::max(e.maxRelError, ok ? 0.0 : 1.0);
      e.inputs += 1;
    } else if (op == DS_DF64_OP_CONSTANTS) {
      const LD pi = 3.141592653589793238462643383279502884L;
      const LD refs[3] = {pi, 2 * pi, pi / 2};
      for (int k = 0; k < 3; ++k) record(k, relError(got(k), refs[k], refs[k]));
    } else if (op == DS_DF64_OP_DOT) {
      const auto [ref, scale] = dotRef(item);
      record(0, relError(got(0), ref, scale));
    } else if (op == DS_DF64_OP_CROSS) {
      for (int k = 0; k < 3; ++k) {
        const auto [ref, scale] = crossRef(item, k);
        record(k, relError(got(k), ref, scale));
      }
    } else {
      for (int k = 0; k < w; ++k) {
        const LD ref = reference(op, value(getA(item, k)), operandB(item, k));
        record(k, relError(got(k), ref, std::fabs(ref)));
      }
    }
  }
  for (Df64OpError& e : errors)
    e.log2 = e.maxRelError > 0 ? std::log2(e.maxRelError) : -std::numeric_limits<double>::infinity();
  return errors;
}

std::vector<Df64ProbeItem> makeFmaItems() {
  // fma(a, b, −fl(a·b)) is the rounding error of a·b when fused and 0 when not; the first item is
  // the classic (1 + 2^-12)² − (1 + 2^-11) = 2^-24. Further items with an unrelated c.
  std::vector<Df64ProbeItem> items;
  auto add = [&](float a, float b, float c) {
    Df64ProbeItem item = makeItem(DS_DF64_OP_FMA, 1);
    item.aHi[0] = a, item.bHi[0] = b, item.aLo[0] = c;
    items.push_back(item);
  };
  add(1.0f + 0x1p-12f, 1.0f + 0x1p-12f, -(1.0f + 0x1p-11f));
  CaseRng r(0xf3au);
  for (int i = 0; i < 255; ++i) {
    const float a = randomFloat(r, -10, 10), b = randomFloat(r, -10, 10);
    add(a, b, i % 2 == 0 ? -(a * b) : randomFloat(r, -12, 12));
  }
  return items;
}

bool fmaResultsExact(std::span<const Df64ProbeItem> items, std::span<const Df64ProbeResult> results) {
  DS_CHECK(items.size() == results.size(), "one fma probe result per item");
  for (std::size_t i = 0; i < items.size(); ++i)
    if (results[i].hi[0] != std::fmaf(items[i].aHi[0], items[i].bHi[0], items[i].aLo[0])) return false;
  return true;
}

}  // namespace dicsynth::gpu::df64
