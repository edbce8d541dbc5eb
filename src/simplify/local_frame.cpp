// Local frame of the simplifier: see local_frame.h.
#include "local_frame.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace interfere::qem {
namespace {

constexpr int kMaxSizeExponent = 20;  // sizes in [2^-20, 2^20] are simplified as they are
constexpr double kMaxOffset = 256;    // as are centres within 256 sizes of the origin

// x - c is exact (Knuth's TwoSum error term is zero) and maps back: (x - c) * 2^k * 2^-k + c == x.
bool exact_coordinate(double x, double c, int k) {
  const double d = x - c;
  const double bv = d - x;
  const double err = (x - (d - bv)) + (-c - bv);
  if (err != 0) return false;
  const double s = std::ldexp(d, k);
  return std::ldexp(s, -k) == d && d + c == x;
}

}  // namespace

Vec3 LocalFrame::to_local(const Vec3& p) const {
  return {std::ldexp(p.x - centre.x, exponent), std::ldexp(p.y - centre.y, exponent),
          std::ldexp(p.z - centre.z, exponent)};
}

Vec3 LocalFrame::to_world(const Vec3& p) const {
  return {std::ldexp(p.x, -exponent) + centre.x, std::ldexp(p.y, -exponent) + centre.y,
          std::ldexp(p.z, -exponent) + centre.z};
}

double LocalFrame::length_to_world(double d) const { return std::ldexp(d, -exponent); }

std::optional<LocalFrame> local_frame(const TriMesh& mesh, const Aabb& box) {
  if (mesh.positions.empty()) return std::nullopt;
  // The size from the largest extent (its square could overflow: no norm), the exponent from it.
  const double size = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
  if (!(size > 0) || !std::isfinite(size)) return std::nullopt;  // one point, or beyond double range
  LocalFrame f;
  f.exponent = -std::ilogb(size);
  const Vec3 mid{box.lo.x / 2 + box.hi.x / 2, box.lo.y / 2 + box.hi.y / 2, box.lo.z / 2 + box.hi.z / 2};
  const double offset = std::max({std::abs(mid.x), std::abs(mid.y), std::abs(mid.z)});
  f.translated = offset > kMaxOffset * size;
  if (std::abs(f.exponent) <= kMaxSizeExponent && !f.translated) return std::nullopt;
  if (f.translated) {
    // c: the centre rounded to a multiple of 2^e, e the size's exponent, so that c has few
    // significant bits and x - c is exact for every x of the part (checked below).
    const int e = std::ilogb(size);
    auto coarse = [e](double v) { return std::ldexp(std::nearbyint(std::ldexp(v, -e)), e); };
    f.centre = {coarse(mid.x), coarse(mid.y), coarse(mid.z)};
  }
  const bool exact = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 1 << 14), true,
      [&](const tbb::blocked_range<std::size_t>& r, bool ok) {
        for (std::size_t i = r.begin(); i < r.end() && ok; ++i) {
          const Vec3& p = mesh.positions[i];
          ok = exact_coordinate(p.x, f.centre.x, f.exponent) && exact_coordinate(p.y, f.centre.y, f.exponent) &&
               exact_coordinate(p.z, f.centre.z, f.exponent);
        }
        return ok;
      },
      [](bool a, bool b) { return a && b; });
  if (!exact) return std::nullopt;
  return f;
}

TriMesh to_local(const TriMesh& mesh, const LocalFrame& frame) {
  TriMesh out;
  out.triangles = mesh.triangles;
  out.positions.resize(mesh.positions.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 1 << 14),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i)
                        out.positions[i] = frame.to_local(mesh.positions[i]);
                    });
  return out;
}

}  // namespace interfere::qem
