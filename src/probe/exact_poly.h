// Exact signs of polynomials in double inputs, for the probe module's cylinder predicates.
//
// The cylinder-triangle decision (cylinder_triangle.cpp) is a Boolean combination of signs of
// polynomials (degree <= 14) in the input doubles. Each polynomial is written once, as a template
// over a number type, and evaluated twice at most:
//  - Filtered: value in double plus a running bound on |value - exact| (Higham, "Accuracy and
//    Stability of Numerical Algorithms", §3.1: |fl(E) - E| <= gamma_n * E~, E~ the expression with
//    every input and operation replaced by its absolute value, n the longest chain of roundings);
//    the sign is returned when |value| exceeds the bound;
//  - Expansion: Shewchuk's floating-point expansions (Discrete Comput. Geom. 18, 1997, §2: Thm 10
//    grow-expansion, two_product by FMA), exact, used only when the filter cannot decide.
// Preconditions as in core/predicates.h: finite inputs, no overflow or underflow.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

namespace interfere::probe::detail {

/// Double value with a certified error bound: |v - exact| <= 2 n u p (u = 2^-53, n u << 1).
struct Filtered {
  double v = 0;  ///< computed value
  double p = 0;  ///< computed permanent (the expression on absolute values)
  int n = 0;     ///< longest chain of roundings
  Filtered() = default;
  explicit Filtered(double x) : v(x), p(std::fabs(x)), n(0) {}
  Filtered(double v_, double p_, int n_) : v(v_), p(p_), n(n_) {}
  double bound() const { return 2.0 * (n + 1) * 0x1p-53 * p; }
  /// -1/0/+1 when certain, 2 when the filter cannot decide.
  int sign() const {
    if (std::fabs(v) > bound()) return (v > 0) - (v < 0);
    if (p == 0) return 0;  // every term has an exactly zero factor
    return 2;
  }
};
inline Filtered operator+(const Filtered& a, const Filtered& b) {
  return {a.v + b.v, a.p + b.p, (a.n > b.n ? a.n : b.n) + 1};
}
inline Filtered operator-(const Filtered& a, const Filtered& b) {
  return {a.v - b.v, a.p + b.p, (a.n > b.n ? a.n : b.n) + 1};
}
inline Filtered operator*(const Filtered& a, const Filtered& b) {
  return {a.v * b.v, a.p * b.p, a.n + b.n + 1};
}
inline Filtered operator-(const Filtered& a) { return {-a.v, a.p, a.n}; }

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

/// e + b (Shewchuk Thm 10, zero elimination).
inline void grow(std::vector<double>& out, const std::vector<double>& e, double b) {
  out.clear();
  double q = b;
  for (double ei : e) {
    double x, y;
    two_sum_(q, ei, x, y);
    if (y != 0) out.push_back(y);
    q = x;
  }
  if (q != 0) out.push_back(q);
}

inline Expansion operator+(const Expansion& a, const Expansion& b) {
  const Expansion& big = a.c.size() >= b.c.size() ? a : b;
  const Expansion& small = a.c.size() >= b.c.size() ? b : a;
  Expansion h = big, tmp;
  for (double f : small.c) {
    grow(tmp.c, h.c, f);
    h.c.swap(tmp.c);
  }
  return h;
}
inline Expansion operator-(const Expansion& a) {
  Expansion r = a;
  for (double& x : r.c) x = -x;
  return r;
}
inline Expansion operator-(const Expansion& a, const Expansion& b) { return a + (-b); }
inline Expansion operator*(const Expansion& a, const Expansion& b) {
  Expansion h, tmp;
  for (double ai : a.c) {
    for (double bj : b.c) {
      const double x = ai * bj;
      const double y = std::fma(ai, bj, -x);
      if (y != 0) {
        grow(tmp.c, h.c, y);
        h.c.swap(tmp.c);
      }
      if (x != 0) {
        grow(tmp.c, h.c, x);
        h.c.swap(tmp.c);
      }
    }
  }
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
