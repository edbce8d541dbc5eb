#include "interfere/core/transform.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "interfere/core/predicates.h"

namespace interfere {

namespace {
std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
std::string matrix_text(const Transform& t) {
  std::string s;
  for (const double x : t.to_row_major()) s += (s.empty() ? "" : " ") + number_text(x);
  return "\"" + s + "\"";
}
}  // namespace

Status Transform::validate() const {
  const std::array<double, 12> v = to_row_major();
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      return Error{.reason = "transform: value " + std::to_string(i + 1) + " is not finite (" + number_text(v[i]) + ")"};
    }
  }
  if (determinant_sign() == 0) {
    return Error{.reason = "transform " + matrix_text(*this) +
                           " is singular (det R = 0): it would collapse the part onto a plane, a line or a point"};
  }
  return {};
}

int Transform::determinant_sign() const {
  // det[r0, r1, r2] = det[r0 - o, r1 - o, r2 - o] with o the origin: orient3d's determinant
  // (Shewchuk's adaptive predicate, exact sign), the subtractions of zero being exact.
  const Vec3 r0{r[0][0], r[0][1], r[0][2]}, r1{r[1][0], r[1][1], r[1][2]}, r2{r[2][0], r[2][1], r[2][2]};
  return orient3d(r0, r1, r2, Vec3{0, 0, 0});
}

std::array<double, 2> Transform::stretch_range() const {
  // Eigenvalues of the symmetric M = R^T·R by cyclic Jacobi rotations (Golub & Van Loan, §8.5);
  // the singular values of R are their square roots.
  double m[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      m[i][j] = 0;
      for (int k = 0; k < 3; ++k) m[i][j] += r[k][i] * r[k][j];
    }
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = std::fabs(m[0][1]) + std::fabs(m[0][2]) + std::fabs(m[1][2]);
    if (off == 0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (m[p][q] == 0) continue;
        const double theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
        const double t = (theta >= 0 ? 1 : -1) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // M <- M·J
          const double mkp = m[k][p], mkq = m[k][q];
          m[k][p] = c * mkp - s * mkq;
          m[k][q] = s * mkp + c * mkq;
        }
        for (int k = 0; k < 3; ++k) {  // M <- J^T·M
          const double mpk = m[p][k], mqk = m[q][k];
          m[p][k] = c * mpk - s * mqk;
          m[q][k] = s * mpk + c * mqk;
        }
      }
  }
  const double lo = std::min({m[0][0], m[1][1], m[2][2]}), hi = std::max({m[0][0], m[1][1], m[2][2]});
  return {std::sqrt(std::max(lo, 0.0)), std::sqrt(std::max(hi, 0.0))};
}

bool Transform::is_rigid() const {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double m = 0;
      for (int k = 0; k < 3; ++k) m += r[k][i] * r[k][j];
      if (std::fabs(m - (i == j ? 1.0 : 0.0)) > 1e-9) return false;
    }
  return determinant_sign() > 0;
}

std::string Transform::non_rigid_note() const {
  if (is_rigid()) return {};
  const auto [lo, hi] = stretch_range();
  std::string what;
  if (hi - lo > 1e-9 * hi || std::fabs(hi - 1) > 1e-9) {
    what = "scales lengths by factors between " + number_text(lo) + " and " + number_text(hi) +
           (hi - lo > 1e-9 * hi ? " (scaled unevenly or sheared)" : "");
  }
  if (determinant_sign() < 0) what += std::string(what.empty() ? "" : " and ") + "mirrors the part (det R < 0)";
  return "transform " + matrix_text(*this) + " is not rigid: it " + what +
         ". The geometry is transformed exactly as given (p' = R p + t) and every distance, clearance and depth "
         "is measured in the transformed space; a simplified part's stored error bound is scaled by the largest "
         "stretch";
}

Expected<Transform> Transform::parse(std::string_view text) {
  std::vector<double> v;
  if (text.find_first_not_of(" ,\t\n\r") == std::string_view::npos) {
    return Error{.reason = "transform: empty (\"" + std::string(text) +
                           "\"); give 12 numbers \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 r22 tz\" or leave the option out"};
  }
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == ',' || c == '\t' || c == '\n' || c == '\r') {
      ++i;
      continue;
    }
    double x = 0;
    const char* first = text.data() + i;
    const auto [ptr, ec] = std::from_chars(first, text.data() + text.size(), x);
    if (ec == std::errc::result_out_of_range) {
      return Error{.reason = "transform: value " + std::to_string(v.size() + 1) + " (\"" +
                             std::string(first, static_cast<std::size_t>(ptr - first)) +
                             "\") is beyond the range of double: not finite"};
    }
    if (ec != std::errc() || ptr == first) {
      return Error{.reason = "transform: not a number at character " + std::to_string(i + 1) +
                             " of \"" + std::string(text) + "\""};
    }
    if (!std::isfinite(x)) {
      return Error{.reason = "transform: value " + std::to_string(v.size() + 1) + " is not finite (\"" +
                             std::string(text) + "\")"};
    }
    v.push_back(x);
    i = static_cast<std::size_t>(ptr - text.data());
  }
  if (v.size() != 12) {
    return Error{.reason = "transform: expected 12 numbers \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 "
                           "r22 tz\", got " +
                           std::to_string(v.size()) + " in \"" + std::string(text) + "\""};
  }
  Transform t;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) t.r[row][col] = v[row * 4 + col];
    t.t[row] = v[row * 4 + 3];
  }
  if (Status ok = t.validate(); !ok) return ok.error();
  return t;
}

std::array<double, 12> Transform::to_row_major() const {
  std::array<double, 12> out{};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out[row * 4 + col] = r[row][col];
    out[row * 4 + 3] = t[row];
  }
  return out;
}

std::array<std::array<double, 4>, 3> Transform::to_rows() const {
  std::array<std::array<double, 4>, 3> out{};
  for (int row = 0; row < 3; ++row) out[row] = {r[row][0], r[row][1], r[row][2], t[row]};
  return out;
}

}  // namespace interfere
