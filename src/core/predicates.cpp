// Exact fallbacks of orient2d/orient3d by floating-point expansion arithmetic (Shewchuk 1997, §2):
// a number is an expansion, a sum of doubles sorted by increasing magnitude and pairwise
// nonoverlapping, so its sign is the sign of its largest (last) component. Operations used:
//  - two_sum / two_diff (Knuth, Thm 7): a+b = x+y exactly, x = fl(a+b);
//  - two_product via fused multiply-add: a*b = x+y exactly, x = fl(a*b), y = fma(a,b,-x);
//  - expansion sum by merging and a chain of two_sums (Thm 13, "fast expansion sum");
//  - scale by a double (Thm 19), products of expansions as sums of scaled copies;
//  all with zero elimination, so inputs whose differences are exact (common: nearby or integer
//  coordinates) stay short. The filters are inline in predicates.h; reaching this file means the
//  filter could not certify the sign.
// Requires round-to-nearest-even double arithmetic and no underflow (see the header).
#include "interfere/core/predicates.h"

#include <atomic>
#include <cmath>

namespace interfere {
namespace {

std::atomic<unsigned long long> g_fallbacks{0};

inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

inline void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double bv = a - x;
  const double av = x + bv;
  y = (a - av) + (bv - b);
}

inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}

/// Exact a - b as an expansion of at most 2 terms; returns its length.
inline int diff_expansion(double a, double b, double* h) {
  double x, y;
  two_diff(a, b, x, y);
  int n = 0;
  if (y != 0) h[n++] = y;
  if (x != 0) h[n++] = x;
  return n;
}

/// h = e + f (Shewchuk Thm 13 with zero elimination). h must hold elen + flen terms and must not
/// alias e or f.
int expansion_sum(int elen, const double* e, int flen, const double* f, double* h) {
  if (elen == 0) {
    for (int i = 0; i < flen; ++i) h[i] = f[i];
    return flen;
  }
  if (flen == 0) {
    for (int i = 0; i < elen; ++i) h[i] = e[i];
    return elen;
  }
  // Merge by increasing magnitude, summing on the fly.
  int ei = 0, fi = 0, hn = 0;
  auto next = [&]() -> double {
    if (fi >= flen || (ei < elen && std::fabs(e[ei]) < std::fabs(f[fi]))) return e[ei++];
    return f[fi++];
  };
  double q = next();
  while (ei < elen || fi < flen) {
    const double g = next();
    double sum, err;
    two_sum(q, g, sum, err);
    if (err != 0) h[hn++] = err;
    q = sum;
  }
  if (q != 0 || hn == 0) h[hn++] = q;
  if (hn == 1 && h[0] == 0) return 0;
  return hn;
}

/// h = e * b (Shewchuk Thm 19 with zero elimination). h must hold 2 * elen terms.
int scale_expansion(int elen, const double* e, double b, double* h) {
  if (elen == 0 || b == 0) return 0;
  int hn = 0;
  double q, lo;
  two_product(e[0], b, q, lo);
  if (lo != 0) h[hn++] = lo;
  for (int i = 1; i < elen; ++i) {
    double p_hi, p_lo, s, s_lo;
    two_product(e[i], b, p_hi, p_lo);
    two_sum(q, p_lo, s, s_lo);
    if (s_lo != 0) h[hn++] = s_lo;
    two_sum(p_hi, s, q, s_lo);  // |p_hi| >= |s| up to rounding: fast_two_sum in the paper
    if (s_lo != 0) h[hn++] = s_lo;
  }
  if (q != 0) h[hn++] = q;
  return hn;
}

/// h = e * f for short expansions (flen <= 2). h must hold 2 * elen * flen terms.
int product_expansion(int elen, const double* e, int flen, const double* f, double* h) {
  if (flen == 0 || elen == 0) return 0;
  if (flen == 1) return scale_expansion(elen, e, f[0], h);
  double t0[64], t1[64];  // 2 * elen <= 64 for every use below
  const int n0 = scale_expansion(elen, e, f[0], t0);
  const int n1 = scale_expansion(elen, e, f[1], t1);
  return expansion_sum(n0, t0, n1, t1, h);
}

inline int expansion_sign(int n, const double* e) {
  if (n == 0) return 0;
  return e[n - 1] > 0 ? 1 : (e[n - 1] < 0 ? -1 : 0);
}

/// Exact 2x2 minor p*s - q*r of 2-term expansions (<= 16 terms).
int minor2(int pn, const double* p, int sn, const double* s, int qn, const double* q, int rn,
           const double* r, double* h) {
  double ps[8], qr[8];
  const int nps = product_expansion(pn, p, sn, s, ps);
  int nqr = product_expansion(qn, q, rn, r, qr);
  for (int i = 0; i < nqr; ++i) qr[i] = -qr[i];
  return expansion_sum(nps, ps, nqr, qr, h);
}

/// Exact det[a-c, b-c] (orient2d's determinant) as an expansion; returns its length (<= 16).
int orient2d_expansion(double ax, double ay, double bx, double by, double cx, double cy,
                       double* det) {
  double acx[2], acy[2], bcx[2], bcy[2];
  const int nacx = diff_expansion(ax, cx, acx), nacy = diff_expansion(ay, cy, acy);
  const int nbcx = diff_expansion(bx, cx, bcx), nbcy = diff_expansion(by, cy, bcy);
  return minor2(nacx, acx, nbcy, bcy, nacy, acy, nbcx, bcx, det);
}

/// Exact w . (u x v) with u = b-a, v = c-a, w = d-a as an expansion (<= 192 terms); this is
/// -det[a-d, b-d, c-d]. Rows are exact differences (<= 2 terms each).
int orient3d_expansion(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double* acc) {
  double u[3][2], v[3][2], w[3][2];
  int nu[3], nv[3], nw[3];
  for (int k = 0; k < 3; ++k) {
    nu[k] = diff_expansion(b[k], a[k], u[k]);
    nv[k] = diff_expansion(c[k], a[k], v[k]);
    nw[k] = diff_expansion(d[k], a[k], w[k]);
  }
  double tmp[192];
  int nacc = 0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    double m[16], t[64];
    // (u x v)_k = u_i v_j - u_j v_i
    const int nm = minor2(nu[i], u[i], nv[j], v[j], nu[j], u[j], nv[i], v[i], m);
    // t = m * w_k (w_k has at most 2 terms)
    int nt = 0;
    if (nw[k] == 1) {
      nt = scale_expansion(nm, m, w[k][0], t);
    } else if (nw[k] == 2) {
      double t0[32], t1[32];
      const int n0 = scale_expansion(nm, m, w[k][0], t0);
      const int n1 = scale_expansion(nm, m, w[k][1], t1);
      nt = expansion_sum(n0, t0, n1, t1, t);
    }
    const int nsum = expansion_sum(nacc, acc, nt, t, tmp);
    for (int s = 0; s < nsum; ++s) acc[s] = tmp[s];
    nacc = nsum;
  }
  return nacc;
}

/// Sum of an expansion's components from the smallest: its value with a relative error of a few
/// units of 2^-53 (the components do not overlap), and the exact sign (the largest component
/// dominates the sum of the others).
double expansion_estimate(int n, const double* e) {
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += e[i];
  return sum;
}

}  // namespace

namespace detail {

int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  g_fallbacks.fetch_add(1, std::memory_order_relaxed);
  double det[16];
  const int n = orient2d_expansion(ax, ay, bx, by, cx, cy, det);
  return expansion_sign(n, det);
}

double orient2d_exact_value(double ax, double ay, double bx, double by, double cx, double cy) {
  g_fallbacks.fetch_add(1, std::memory_order_relaxed);
  double det[16];
  const int n = orient2d_expansion(ax, ay, bx, by, cx, cy, det);
  return expansion_estimate(n, det);
}

int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  g_fallbacks.fetch_add(1, std::memory_order_relaxed);
  double acc[192];
  const int n = orient3d_expansion(a, b, c, d, acc);
  return -expansion_sign(n, acc);  // Shewchuk's sign: det[a-d, b-d, c-d] = -(w . (u x v))
}

double orient3d_exact_value(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  g_fallbacks.fetch_add(1, std::memory_order_relaxed);
  double acc[192];
  const int n = orient3d_expansion(a, b, c, d, acc);
  return -expansion_estimate(n, acc);
}

}  // namespace detail

unsigned long long exact_fallback_count() {
  return g_fallbacks.load(std::memory_order_relaxed);
}

}  // namespace interfere
