// Exact signs of polynomials in double inputs, for the probe module's cylinder predicates.
//
// The cylinder-triangle decision (cylinder_triangle.cpp) is a Boolean combination of signs of
// polynomials (degree <= 10) in the input doubles. Each polynomial is written once, as a template
// over a number type, and evaluated twice at most:
//  - Filtered: value in double plus a running bound on |value - exact| (running error analysis,
//    below); the sign is returned when |value| exceeds the bound;
//  - Expansion: Shewchuk's floating-point expansions (Discrete Comput. Geom. 18, 1997, §2: Thm 10
//    grow-expansion, two_product by FMA), exact, used only when the filter cannot decide.
// Preconditions as in core/predicates.h: finite inputs, no overflow or underflow.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

namespace interfere::probe::detail {

/// Double value with a certified absolute error bound, by running error analysis (Higham,
/// "Accuracy and Stability of Numerical Algorithms", §3.3): for x = a op b computed as fl(x),
///   add/sub: e = e_a + e_b + u |fl(x)|
///   mul:     e = |a| e_b + |b| e_a + e_a e_b + u |fl(x)|
/// with u = 2^-53, each bound scaled by (1 + 2^-49) to cover the rounding of its own evaluation
/// (at most 4 roundings of nonnegative terms). Unlike a static permanent-based bound, the bound
/// follows the actual magnitudes of intermediate values, so an early cancellation (a cross product
/// of nearly parallel vectors) does not inflate every later bound. Exact inputs carry e = 0, and a
/// value whose bound is 0 is exact (its sign, including 0, is certain).
struct Filtered {
  double v = 0;  ///< computed value
  double e = 0;  ///< bound on |v - exact|
  Filtered() = default;
  explicit Filtered(double x) : v(x), e(0) {}
  Filtered(double v_, double e_) : v(v_), e(e_) {}
  /// -1/0/+1 when certain, 2 when the filter cannot decide.
  int sign() const {
    if (std::fabs(v) > e) return (v > 0) - (v < 0);
    if (e == 0) return 0;  // exact zero
    return 2;
  }
};
inline constexpr double kUnit = 0x1p-53;
inline constexpr double kGrow = 1 + 0x1p-49;
inline Filtered operator+(const Filtered& a, const Filtered& b) {
  const double v = a.v + b.v;
  return {v, (a.e + b.e + kUnit * std::fabs(v)) * kGrow};
}
inline Filtered operator-(const Filtered& a, const Filtered& b) {
  const double v = a.v - b.v;
  return {v, (a.e + b.e + kUnit * std::fabs(v)) * kGrow};
}
inline Filtered operator*(const Filtered& a, const Filtered& b) {
  const double v = a.v * b.v;
  return {v, (std::fabs(a.v) * b.e + std::fabs(b.v) * a.e + a.e * b.e + kUnit * std::fabs(v)) * kGrow};
}
inline Filtered operator-(const Filtered& a) { return {-a.v, a.e}; }

/// Exact real number as a nonoverlapping expansion, components by increasing magnitude, no zeros.
struct Expansion {
  std::vector<double> c;
  Expansion() = default;
  explicit Expansion(double x) {
    if (x != 0) c.push_back(x);
  }
  int sign() const { return c.empty() ? 0 : (c.back() > 0 ? 1 : -1); }
};

inline void two_sum_(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

/// e + f: merge by magnitude and a chain of two_sums with zero elimination (Shewchuk Thm 13, as
/// in src/core/predicates.cpp). Linear time.
inline void expansion_sum(const std::vector<double>& e, const std::vector<double>& f, std::vector<double>& h) {
  h.clear();
  if (e.empty()) {
    h = f;
    return;
  }
  if (f.empty()) {
    h = e;
    return;
  }
  std::size_t ei = 0, fi = 0;
  auto next = [&]() -> double {
    if (fi >= f.size() || (ei < e.size() && std::fabs(e[ei]) < std::fabs(f[fi]))) return e[ei++];
    return f[fi++];
  };
  double q = next();
  while (ei < e.size() || fi < f.size()) {
    const double g = next();
    double sum, err;
    two_sum_(q, g, sum, err);
    if (err != 0) h.push_back(err);
    q = sum;
  }
  if (q != 0) h.push_back(q);
}

/// e * b (Shewchuk Thm 19, two_product by FMA, zero elimination). Linear time.
inline void scale_expansion(const std::vector<double>& e, double b, std::vector<double>& h) {
  h.clear();
  if (e.empty() || b == 0) return;
  double q = e[0] * b;
  double lo = std::fma(e[0], b, -q);
  if (lo != 0) h.push_back(lo);
  for (std::size_t i = 1; i < e.size(); ++i) {
    const double p_hi = e[i] * b;
    const double p_lo = std::fma(e[i], b, -p_hi);
    double s, s_lo;
    two_sum_(q, p_lo, s, s_lo);
    if (s_lo != 0) h.push_back(s_lo);
    two_sum_(p_hi, s, q, s_lo);
    if (s_lo != 0) h.push_back(s_lo);
  }
  if (q != 0) h.push_back(q);
}

inline Expansion operator+(const Expansion& a, const Expansion& b) {
  Expansion h;
  expansion_sum(a.c, b.c, h.c);
  return h;
}
inline Expansion operator-(const Expansion& a) {
  Expansion r = a;
  for (double& x : r.c) x = -x;
  return r;
}
inline Expansion operator-(const Expansion& a, const Expansion& b) { return a + (-b); }
/// Product: one scaled copy per component of the shorter factor, summed pairwise (tree).
inline Expansion operator*(const Expansion& a, const Expansion& b) {
  const Expansion& big = a.c.size() >= b.c.size() ? a : b;
  const Expansion& small = a.c.size() >= b.c.size() ? b : a;
  std::vector<std::vector<double>> parts(small.c.size());
  for (std::size_t i = 0; i < small.c.size(); ++i) scale_expansion(big.c, small.c[i], parts[i]);
  std::vector<double> tmp;
  for (std::size_t step = 1; step < parts.size(); step *= 2) {
    for (std::size_t i = 0; i + step < parts.size(); i += 2 * step) {
      expansion_sum(parts[i], parts[i + step], tmp);
      parts[i].swap(tmp);
    }
  }
  Expansion h;
  if (!parts.empty()) h.c = std::move(parts[0]);
  return h;
}

/// Small 3-vector over a number type.
template <class N>
struct V3 {
  N x, y, z;
};
template <class N>
V3<N> operator+(const V3<N>& a, const V3<N>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class N>
V3<N> operator-(const V3<N>& a, const V3<N>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class N>
V3<N> scale(const N& s, const V3<N>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class N>
N dot(const V3<N>& a, const V3<N>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class N>
V3<N> cross(const V3<N>& a, const V3<N>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace interfere::probe::detail
