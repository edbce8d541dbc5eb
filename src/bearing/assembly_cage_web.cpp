// The cage web rows of a bearing assembly (assembly_cage_web.h; issue #27): moved out of
// assembly_pairs.cpp, the same functions and operations (the same bits).
#include "assembly_cage_web.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "golden.h"
#include "interfere/bearing/raceway.h"
#include "interfere/bearing/scarred.h"
#include "interfere/np/distance.h"

namespace interfere::bearing::detail {
namespace {

/// min over the triangle (t0, t1, t2) of the convex signed distance sd: nested golden-section search
/// over the barycentric coordinates (partial minimisation keeps convexity).
template <class F>
std::pair<double, Vec3> triangle_min(F&& sd, const Vec3& t0, const Vec3& t1, const Vec3& t2) {
  constexpr int kIter = 72;
  const auto at = [&](double u, double v) { return t0 + (t1 - t0) * u + (t2 - t0) * v; };
  const auto over_v = [&](double u) {
    return golden_min([&](double v) { return sd(at(u, v)); }, 0.0, 1.0 - u, kIter);
  };
  const auto [u, value] = golden_min([&](double uu) { return over_v(uu).second; }, 0.0, 1.0, kIter);
  const double v = over_v(u).first;
  return {value, at(u, v)};
}

/// The distance from the segment [s0, s1] to the triangle t: the smallest of the end points'
/// distances to t, the segment's distances to t's edges and, where the segment crosses t's plane, the
/// crossing point's distance to t (Ericson 2005, §5.1.5 and §5.1.9: a closest pair has a point at an
/// end of the segment, on an edge of t, or is a crossing). Constructions in double.
double segment_triangle_distance(const Vec3& s0, const Vec3& s1, const std::array<Vec3, 3>& t) {
  double d = std::min(norm(s0 - closest_point_on_triangle(s0, t)), norm(s1 - closest_point_on_triangle(s1, t)));
  for (int i = 0; i < 3; ++i) d = std::min(d, segment_segment_closest(s0, s1, t[i], t[(i + 1) % 3]).distance);
  const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
  const double e0 = dot(s0 - t[0], n), e1 = dot(s1 - t[0], n);
  if (((e0 <= 0 && e1 >= 0) || (e0 >= 0 && e1 <= 0)) && e0 != e1) {
    const Vec3 x = s0 + (s1 - s0) * (e0 / (e0 - e1));
    d = std::min(d, norm(x - closest_point_on_triangle(x, t)));
  }
  return d;
}

/// The distance from the origin to the planar triangle (a, b, c) (2D points): 0 inside, else the
/// nearest of its edges (issue #27, speed: web_distance's projected bound).
double origin_triangle_distance_2d(const std::array<double, 2>& a, const std::array<double, 2>& b,
                                   const std::array<double, 2>& c) {
  const auto cross2 = [](const std::array<double, 2>& p, const std::array<double, 2>& q) {
    return p[0] * q[1] - p[1] * q[0];
  };
  // the origin's side of each edge (the orientation of (p, q, origin) is cross2(p, q))
  const double s0 = cross2(a, b), s1 = cross2(b, c), s2 = cross2(c, a);
  if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return 0;
  const auto edge = [](const std::array<double, 2>& p, const std::array<double, 2>& q) {
    const double dx = q[0] - p[0], dy = q[1] - p[1], l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(-(p[0] * dx + p[1] * dy) / l2, 0.0, 1.0) : 0.0;
    const double x = p[0] + dx * t, y = p[1] + dy * t;
    return std::sqrt(x * x + y * y);
  };
  return std::min({edge(a, b), edge(b, c), edge(c, a)});
}

/// The closed form of web_distance for a web apart from the roller across one of its faces (issue
/// #27, speed; docs/bearing.md "Cage webs in closed form"). The web is {x : n_j.x <= d_j, j = 0..5}.
/// For a face j, g_j = min over the roller of n_j.x - d_j is the support function of the roller (a
/// cylinder or frustum is the convex hull of its end circles: the lowest point is on the rim of the
/// lower end, x* = end centre - r_end (n_j - (n_j.u) u) / |n_j - (n_j.u) u|). When g_j > 0 the
/// plane n_j.x = d_j separates the two solids, so every web point is at least g_j from the roller;
/// when moreover the foot p* = x* - g_j n_j lies in the web (inside every other face plane, by a
/// margin far above rounding), p* is a web point at distance g_j from the roller point x*: the
/// distance of the two solids, hence the minimum over the web's triangles of the roller's signed
/// distance (web_distance's value; apart, the web's centre is outside the roller), exact to
/// rounding. nullopt when no face certifies it (overlapping solids, a foot past a face's edge): the
/// triangle minima decide. Only the face of the largest g_j can certify (the distance is >= every
/// g_j, and a certified one equals it).
std::optional<WebValue> separated_web(const Cylinder& roller, const CageWeb& web, const Transform& cage_pose) {
  std::array<Vec3, 6> n;
  std::array<double, 6> d{};
  int best = -1;
  double g = 0;
  Vec3 low;
  const Vec3 top = roller.top_center();
  for (int j = 0; j < 6; ++j) {
    n[j] = cage_pose.rotate(web.normals[j]);
    d[j] = web.offsets[j] + dot(n[j], cage_pose.t);
    // (issue #27, speed) g_j <= n_j.base - d_j, also as computed (subtracting r s >= 0 and taking
    // a min round down, rounding is monotone): a face whose bound is not above g cannot be taken
    const double nb = dot(n[j], roller.base);
    if (!(nb - d[j] > g)) continue;
    const double cu = std::clamp(dot(n[j], roller.axis), -1.0, 1.0), s = std::sqrt(std::max(0.0, 1 - cu * cu));
    const double vb = nb - roller.radius * s, vt = dot(n[j], top) - roller.top() * s;
    const double gj = std::min(vb, vt) - d[j];
    if (!(gj > g)) continue;
    g = gj, best = j;
    const Vec3 w = n[j] - roller.axis * cu;
    const double wn = norm(w);
    low = vb <= vt ? roller.base : top;
    if (wn > 0) low = low - w * ((vb <= vt ? roller.radius : roller.top()) / wn);
  }
  if (best < 0) return std::nullopt;
  const Vec3 foot = low - n[best] * g;
  const double scale = std::max({std::fabs(foot.x), std::fabs(foot.y), std::fabs(foot.z)}) + roller.height +
                       roller.max_radius();
  const double margin = 0x1p-36 * scale;
  int outside = -1;
  for (int k = 0; k < 6; ++k)
    if (k != best && !(dot(n[k], foot) - d[k] < -margin)) {
      if (outside >= 0 || (k ^ 1) == best) return std::nullopt;
      outside = k;
    }
  WebValue out;
  if (outside < 0) {
    out.distance = g;
    out.point_b = foot;
    out.point_a = roller.tapered() ? nearest_on_frustum_boundary(roller, foot) : nearest_on_cylinder_boundary(roller, foot);
    return out;
  }
  // the foot lies past one neighbouring face k (a roller overhanging the web's end): the nearest web
  // point is then looked for on the edge where faces j and k meet, against the cylinder's side (the
  // closest points of that edge and the roller's axis segment). A candidate pair (p on the web, x
  // on the roller) at distance D is certified by its direction v = (x - p) / D: every web point has
  // v.w <= max over the web's corners of v.c, every roller point v.y >= the roller's support in
  // direction v (its end circles), so the distance of the solids is at least
  // L = min_roller v.y - max_web v.w; accepted when D - L is within rounding of the scale
  if (roller.tapered()) return std::nullopt;
  std::array<Vec3, 2> edge;
  int ne = 0;
  for (int i = 0; i < 8; ++i)
    if (((i >> (best / 2)) & 1) == best % 2 && ((i >> (outside / 2)) & 1) == outside % 2)
      edge[static_cast<std::size_t>(ne++)] = cage_pose.apply(web.corners[static_cast<std::size_t>(i)]);
  const ClosestPoints ep = segment_segment_closest(edge[0], edge[1], roller.base, roller.top_center());
  const Vec3 p = ep.p, x = nearest_on_cylinder_boundary(roller, p);
  const double dist = norm(x - p);
  if (!(dist > 0)) return std::nullopt;
  const Vec3 v = (x - p) / dist;
  double web_max = -std::numeric_limits<double>::infinity();
  for (const Vec3& c : web.corners) web_max = std::max(web_max, dot(v, cage_pose.apply(c)));
  const double cu = std::clamp(dot(v, roller.axis), -1.0, 1.0), sv = std::sqrt(std::max(0.0, 1 - cu * cu));
  const double roller_min = std::min(dot(v, roller.base), dot(v, roller.top_center())) - roller.radius * sv;
  const double lower = roller_min - web_max;
  if (!(lower > 0) || !(dist - lower <= 0x1p-44 * scale)) return std::nullopt;
  // the solids' distance lies in [lower, dist]: the row reports the certified lower end, so a
  // clearance threshold inside that 2^-44 band can only make the verdict stricter, never clear
  // (review of 2ee6680; the point pair is dist apart)
  out.distance = lower;
  out.point_a = x, out.point_b = p;
  return out;
}

/// The web's deepest point in an overlapping cylinder in closed form (issue #27, speed;
/// docs/bearing.md "Cage webs in closed form"): inside the roller the depth is min(R - rho, z, h - z)
/// (rho the distance to the axis line, z along it), at most R - rho. The web point nearest the axis
/// line: the corners projected along the axis give a convex polygon (its hull), whose point q nearest
/// the axis is on an edge (c_a, c_b): x = c_a + lambda (c_b - c_a) is a web point over q, moved along
/// the axis within the web (the line's interval in the six face planes) to the z nearest h/2. With
/// v the unit direction from the axis to q (across the axis), every web point has rho >= v.(w -
/// base) >= L = min over the corners, so the depth anywhere in the web is at most R - L; when at x
/// the radial piece binds (min(z, h - z) >= R - rho(x) + margin) and rho(x) - L is within 2^-44 of
/// the scale, the largest depth is R - rho(x), exact to rounding, and the row's value (the minimum
/// of the roller's signed distance over the web) is rho(x) - R. nullopt otherwise (the axis through
/// the web, an end piece binding, a tapered roller): the triangle minima decide.
std::optional<WebValue> deepest_web_point(const Cylinder& roller, const CageWeb& web, const Transform& cage_pose) {
  if (roller.tapered()) return std::nullopt;
  const Vec3& u = roller.axis;
  const Vec3 t1 = std::fabs(u.x) < 0.9 ? cross(u, Vec3{1, 0, 0}) : cross(u, Vec3{0, 1, 0});
  const Vec3 e1 = t1 / norm(t1), e2 = cross(u, e1);
  std::array<Vec3, 8> c;
  std::array<std::array<double, 2>, 8> q{};
  for (int i = 0; i < 8; ++i) {
    c[i] = cage_pose.apply(web.corners[static_cast<std::size_t>(i)]);
    const Vec3 d = c[i] - roller.base;
    q[i] = {dot(d, e1), dot(d, e2)};
  }
  // the nearest point to the origin of the projected corners' hull: every segment between two
  // corners (28; the hull's edges are among them), the nearest point of the nearest segment; the
  // origin inside the hull (the axis through the web) is refused by the certificate below (L < 0)
  double best = std::numeric_limits<double>::infinity();
  int ia = 0, ib = 0;
  double lambda = 0;
  for (int a = 0; a < 8; ++a)
    for (int b = a; b < 8; ++b) {
      const double dx = q[b][0] - q[a][0], dy = q[b][1] - q[a][1], l2 = dx * dx + dy * dy;
      const double t = l2 > 0 ? std::clamp(-(q[a][0] * dx + q[a][1] * dy) / l2, 0.0, 1.0) : 0.0;
      const double px = q[a][0] + dx * t, py = q[a][1] + dy * t, r2 = px * px + py * py;
      if (r2 < best) best = r2, ia = a, ib = b, lambda = t;
    }
  Vec3 x = c[ia] + (c[ib] - c[ia]) * lambda;
  const Vec3 dx = x - roller.base;
  const double z0 = dot(dx, u);
  Vec3 radial = dx - u * z0;
  const double rn = norm(radial);
  if (!(rn > 0) || !(rn < roller.radius)) return std::nullopt;
  const Vec3 v = radial / rn;
  double lower = std::numeric_limits<double>::infinity();
  for (const Vec3& ci : c) lower = std::min(lower, dot(v, ci - roller.base));
  // the web's interval on the line x + t u, and the t whose z is nearest h / 2
  double tlo = -std::numeric_limits<double>::infinity(), thi = std::numeric_limits<double>::infinity();
  for (int j = 0; j < 6; ++j) {
    const Vec3 n = cage_pose.rotate(web.normals[static_cast<std::size_t>(j)]);
    const double dj = web.offsets[static_cast<std::size_t>(j)] + dot(n, cage_pose.t);
    const double nu = dot(n, u), gap = dj - dot(n, x);  // n.(x + t u) <= dj
    if (nu > 0) thi = std::min(thi, gap / nu);
    else if (nu < 0) tlo = std::max(tlo, gap / nu);
    else if (gap < 0) return std::nullopt;
  }
  const double t = std::clamp(0.5 * roller.height - z0, std::min(0.0, tlo), std::max(0.0, thi));
  x = x + u * t;
  const double z = dot(x - roller.base, u);
  const Vec3 rad = (x - roller.base) - u * z;
  const double rho = norm(rad);
  const double scale = std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)}) + roller.height + roller.radius;
  if (!(lower > 0) || !(rho - lower <= 0x1p-44 * scale)) return std::nullopt;
  if (!(std::min(z, roller.height - z) >= roller.radius - rho + 0x1p-36 * scale)) return std::nullopt;
  WebValue out;
  out.distance = rho - roller.radius;
  out.point_b = x;
  out.point_a = roller.base + u * z + rad * (roller.radius / rho);
  return out;
}

}  // namespace

WebValue web_distance(const Cylinder& roller, const TriMesh& web, const Transform& cage_pose,
                      const CageWeb* faces) {
  if (faces)
    if (std::optional<WebValue> v = separated_web(roller, *faces, cage_pose)) return *v;
  if (faces)
    if (std::optional<WebValue> v = deepest_web_point(roller, *faces, cage_pose)) return *v;
  WebValue out;
  // the posed corners (webs have 8: no allocation per call; issue #27, speed)
  std::array<Vec3, 8> small;
  std::vector<Vec3> large;
  if (web.positions.size() > small.size()) large.resize(web.positions.size());
  Vec3* const p = large.empty() ? small.data() : large.data();
  const std::size_t np = web.positions.size();
  Vec3 centre;
  for (std::size_t i = 0; i < np; ++i) p[i] = cage_pose.apply(web.positions[i]), centre += p[i];
  centre = centre / static_cast<double>(np);
  if (!roller.tapered()) {
    // sd_roller(x) >= dist(x, axis segment) - radius everywhere (the roller lies in the capsule
    // around its axis; inside, rho - R <= -min(R - rho, z, h - z)), so a triangle's bounding sphere
    // gives a lower bound of its minimum: triangles whose bound is not below the best exact value
    // so far are skipped (the value is the same, only the work is less; ties keep the first).
    std::array<std::pair<double, std::size_t>, 64> order{};
    const std::size_t nt = std::min<std::size_t>(web.triangles.size(), order.size());
    for (std::size_t i = 0; i < nt; ++i) {
      const Tri& t = web.triangles[i];
      const Vec3 c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3.0;
      const double rad = std::max({norm(p[t[0]] - c), norm(p[t[1]] - c), norm(p[t[2]] - c)});
      const double along = std::clamp(dot(c - roller.base, roller.axis), 0.0, roller.height);
      const Vec3 foot = roller.base + roller.axis * along;
      order[i] = {norm(c - foot) - rad - roller.radius - 1e-9 * (1 + norm(c - roller.base) + roller.height), i};
    }
    std::sort(order.begin(), order.begin() + nt);
    // the corners projected across the roller's axis (coordinates about the axis), for the
    // projected bound below; computed on first use
    std::array<std::array<double, 2>, 8> q2{};
    std::vector<std::array<double, 2>> q2_large;
    std::array<double, 2>* q = nullptr;
    const auto projected = [&] {
      if (q) return q;
      if (np > q2.size()) q2_large.resize(np);
      q = q2_large.empty() ? q2.data() : q2_large.data();
      const Vec3& u = roller.axis;
      const Vec3 t1 = std::fabs(u.x) < 0.9 ? cross(u, Vec3{1, 0, 0}) : cross(u, Vec3{0, 1, 0});
      const Vec3 e1 = t1 / norm(t1), e2 = cross(u, e1);
      for (std::size_t i = 0; i < np; ++i) q[i] = {dot(p[i] - roller.base, e1), dot(p[i] - roller.base, e2)};
      return q;
    };
    for (std::size_t k = 0; k < nt; ++k) {
      if (!(order[k].first < out.distance)) break;
      const Tri& t = web.triangles[order[k].second];
      // once a value is known, the same bound with the triangle's exact distance to the axis segment
      // (dist(x, segment) - radius <= sd_roller(x)) skips most of the rest (issue #27, speed: 11.2
      // of 12 triangles were solved per web). Skipped triangles are those whose value could not be
      // below the best: the value and the first triangle reaching it are the same as without it
      if (out.distance < std::numeric_limits<double>::infinity()) {
        const Vec3 c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3.0;
        const double margin = 1e-9 * (1 + norm(c - roller.base) + roller.height);
        // two cheaper lower bounds first (issue #27, speed; the same margin, so a triangle they skip
        // could not be below the best either): the roller lies in its slab 0 <= z <= h, so
        // sd_roller >= max(-z, z - h), over the triangle >= max(-z_max, z_min - h) (z linear, over
        // its corners); and when the axis segment lies on one side of the triangle's plane, its
        // distance to the triangle is at least its ends' smaller distance to the plane
        const double z0 = dot(p[t[0]] - roller.base, roller.axis), z1 = dot(p[t[1]] - roller.base, roller.axis),
                     z2 = dot(p[t[2]] - roller.base, roller.axis);
        if (!(std::max(-std::max({z0, z1, z2}), std::min({z0, z1, z2}) - roller.height) - margin < out.distance)) continue;
        const Vec3 top = roller.top_center();
        const Vec3 tn = cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
        const double tl = norm(tn);
        if (tl > 0) {
          const double e0 = dot(roller.base - p[t[0]], tn) / tl, e1 = dot(top - p[t[0]], tn) / tl;
          if ((e0 > 0) == (e1 > 0) && e0 != 0 && e1 != 0 &&
              !(std::min(std::fabs(e0), std::fabs(e1)) - roller.radius - margin < out.distance))
            continue;
        }
        // (issue #27, speed) a point's distance to the axis segment is at least its distance to the
        // axis line, i.e. to the origin of the plane across the axis: at least the projected
        // triangle's distance from it (a few flops against the segment-triangle distance's ~400;
        // the same margin, so a triangle it skips could not be below the best either)
        {
          const std::array<double, 2>* qq = projected();
          if (!(origin_triangle_distance_2d(qq[t[0]], qq[t[1]], qq[t[2]]) - roller.radius - margin < out.distance))
            continue;
        }
        const double seg = segment_triangle_distance(roller.base, top, {p[t[0]], p[t[1]], p[t[2]]});
        if (!(seg - roller.radius - margin < out.distance)) continue;
      }
      const TriangleMin tm = triangle_min_signed_distance(roller, p[t[0]], p[t[1]], p[t[2]]);
      if (tm.value < out.distance) out.distance = tm.value, out.point_b = tm.point;
    }
    for (std::size_t i = nt; i < web.triangles.size(); ++i) {  // (webs have 12 triangles)
      const Tri& t = web.triangles[i];
      const TriangleMin tm = triangle_min_signed_distance(roller, p[t[0]], p[t[1]], p[t[2]]);
      if (tm.value < out.distance) out.distance = tm.value, out.point_b = tm.point;
    }
  } else {
    // A frustum lies in the cylinder of its larger radius, so that cylinder's exact triangle minimum
    // is a lower bound of the frustum's: triangles whose bound is not below the best value so far
    // are skipped (the value is the same, only the work is less).
    Cylinder enclosing = roller;
    enclosing.radius = roller.max_radius();
    enclosing.top_radius = -1;
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t i = 0; i < web.triangles.size(); ++i) {
      const Tri& t = web.triangles[i];
      order.emplace_back(triangle_min_signed_distance(enclosing, p[t[0]], p[t[1]], p[t[2]]).value, i);
    }
    std::sort(order.begin(), order.end());
    for (const auto& [bound, i] : order) {
      if (!(bound < out.distance)) break;
      const Tri& t = web.triangles[i];
      const auto [value, point] = triangle_min(
          [&](const Vec3& x) { return point_frustum_signed_distance(roller, x); }, p[t[0]], p[t[1]], p[t[2]]);
      if (value < out.distance) out.distance = value, out.point_b = point;
    }
  }
  if (out.distance > 0) {
    const double c = roller.tapered() ? point_frustum_signed_distance(roller, centre) : point_signed_distance(roller, centre);
    if (c < 0) out.distance = c, out.point_b = centre;  // the web inside the roller: a clash
  }
  out.point_a = roller.tapered() ? nearest_on_frustum_boundary(roller, out.point_b)
                                 : nearest_on_cylinder_boundary(roller, out.point_b);
  return out;
}

namespace {

/// fwd of a roller and a convex web: max over the roller of F(x) = min_j (d_j - n_j.x), the depth of
/// x in the web when F >= 0 (a convex polytope's interior depth is its smallest face-plane
/// distance). F is concave and the roller convex, so G(tau) = max of F over the roller's disk at axial
/// parameter tau is concave (partial maximisation over the fibres): a golden-section search over tau.
/// On a disk |y| <= rho, F = min_j (b_j - m_j.y) is maximised at a point where one piece is maximised
/// on the circle (y = -rho m_j/|m_j|), where two pieces are equal on the circle, or where three are
/// equal inside (a vertex of the arrangement), or at the centre (pieces constant): all enumerated,
/// exact to rounding. Returns (F max, its point).
std::pair<double, Vec3> deepest_in_web(const Cylinder& roller, const std::array<Vec3, 6>& n, const std::array<double, 6>& d) {
  const Vec3 u = roller.axis;
  const Vec3 t1 = std::fabs(u.x) < 0.9 ? cross(u, Vec3{1, 0, 0}) : cross(u, Vec3{0, 1, 0});
  const Vec3 e1 = t1 / norm(t1), e2 = cross(u, e1);
  std::array<double, 6> mx{}, my{}, ml{};
  for (int j = 0; j < 6; ++j) mx[j] = dot(n[j], e1), my[j] = dot(n[j], e2), ml[j] = std::hypot(mx[j], my[j]);
  // what does not depend on tau, once per call (issue #27, speed; the same operations on the same
  // operands as when it was computed per disk, so the same values)
  struct PairTerms {
    double wx, wy, w2;
  };
  std::array<std::array<PairTerms, 6>, 6> pt{};
  std::array<std::array<std::array<double, 6>, 6>, 6> det{};
  for (int i = 0; i < 6; ++i)
    for (int j = i + 1; j < 6; ++j) {
      const double wx = mx[j] - mx[i], wy = my[j] - my[i];
      pt[i][j] = {wx, wy, wx * wx + wy * wy};
      for (int k = j + 1; k < 6; ++k) det[i][j][k] = wx * (my[k] - my[i]) - wy * (mx[k] - mx[i]);
    }
  const auto disk = [&](double tau, Vec3* at) {
    const Vec3 c = roller.base + u * tau;
    const double rho = roller.radius + (roller.top() - roller.radius) * tau / roller.height;
    std::array<double, 6> b{};
    for (int j = 0; j < 6; ++j) b[j] = d[j] - dot(n[j], c);
    double best = -std::numeric_limits<double>::infinity(), bx = 0, by = 0;
    const auto take = [&](double x, double y) {
      double f = std::numeric_limits<double>::infinity();
      for (int j = 0; j < 6; ++j) {
        f = std::min(f, b[j] - mx[j] * x - my[j] * y);
        if (!(f > best)) return;  // (f only decreases: this candidate cannot replace the best)
      }
      best = f, bx = x, by = y;
    };
    take(0, 0);
    for (int j = 0; j < 6; ++j)
      if (const double l = ml[j]; l > 0) take(-rho * mx[j] / l, -rho * my[j] / l);
    for (int i = 0; i < 6; ++i)
      for (int j = i + 1; j < 6; ++j) {
        const auto [wx, wy, w2] = pt[i][j];
        const double beta = b[j] - b[i];
        if (!(w2 > 0)) continue;
        const double x0 = beta * wx / w2, y0 = beta * wy / w2, h2 = rho * rho - beta * beta / w2;
        if (h2 >= 0) {
          const double s = std::sqrt(h2 / w2);
          take(x0 - wy * s, y0 + wx * s);
          take(x0 + wy * s, y0 - wx * s);
        }
        for (int k = j + 1; k < 6; ++k) {
          const double vx = mx[k] - mx[i], vy = my[k] - my[i], gamma = b[k] - b[i], dt = det[i][j][k];
          if (dt == 0) continue;
          const double x = (beta * vy - wy * gamma) / dt, y = (wx * gamma - beta * vx) / dt;
          if (x * x + y * y <= rho * rho) take(x, y);
        }
      }
    if (at) *at = c + e1 * bx + e2 * by;
    return best;
  };
  const auto [tau, neg] = golden_min([&](double t) { return -disk(t, nullptr); }, 0.0, roller.height, 100);
  Vec3 at;
  const double best = disk(tau, &at);
  (void)neg;
  return {best, at};
}

/// The roller's deepest point in the convex web in closed form (issue #27, speed; docs/bearing.md
/// "Cage webs in closed form"): max over the roller of F(x) = min_j a_j(x), a_j(x) = d_j - n_j.x.
/// (1) One face: x_j, the roller's point lowest along n_j (on the rim of an end circle), maximises
/// a_j over the roller; when every other a_k(x_j) is above a_j(x_j) (by a margin far above
/// rounding), F <= a_j <= a_j(x_j) = F(x_j) everywhere: the maximum. (2) Two faces (a cylinder
/// overhanging the web's end face k while pressed into face j): when x_j has a_k < a_j and x_k has
/// a_j < a_k, the maximum of the concave min(a_j, a_k) has a_j = a_k, i.e. it is the largest a_j
/// over the roller cut by the plane H: (n_j - n_k).x = d_j - d_k, attained on the boundary of that
/// section; for the side's ellipse c + R e cos t + R (w - u (m.w)/(m.u)) sin t (c the axis point
/// in H, m H's unit normal, e = u x m / |u x m|, w = u x e) the largest a_j is at (cos t, sin t) =
/// -(n_j.A, n_j.B)/|.|: when that point lies within the roller's length (by the margin) it is the
/// maximum over the section, and when the other four faces are above it there, F's maximum.
/// Returns false when neither certifies (deepest_in_web searches).
bool deepest_closed_form(const Cylinder& roller, const std::array<Vec3, 6>& n, const std::array<double, 6>& d,
                         double& fwd, Vec3& at) {
  const double scale = std::max({std::fabs(roller.base.x), std::fabs(roller.base.y), std::fabs(roller.base.z)}) +
                       roller.height + roller.max_radius();
  const double margin = 0x1p-36 * scale;
  const auto lowest = [&](const Vec3& nj) {  // the roller point lowest along nj
    const double cu = std::clamp(dot(nj, roller.axis), -1.0, 1.0);
    const double s = std::sqrt(std::max(0.0, 1 - cu * cu));
    const bool base = dot(nj, roller.base) - roller.radius * s <= dot(nj, roller.top_center()) - roller.top() * s;
    Vec3 x = base ? roller.base : roller.top_center();
    const Vec3 w = nj - roller.axis * cu;
    if (const double wn = norm(w); wn > 0) x = x - w * ((base ? roller.radius : roller.top()) / wn);
    return x;
  };
  const auto a = [&](int j, const Vec3& x) { return d[j] - dot(n[j], x); };
  // the face whose reach is smallest (two_sided_web's bound)
  int j = 0;
  std::array<Vec3, 6> low;
  std::array<double, 6> reach{};
  for (int k = 0; k < 6; ++k) {
    low[k] = lowest(n[k]), reach[k] = a(k, low[k]);
    if (reach[k] < reach[j]) j = k;
  }
  int below = -1;
  for (int k = 0; k < 6; ++k)
    if (k != j && !(a(k, low[j]) > reach[j] + margin)) {
      if (below >= 0) return false;
      below = k;
    }
  if (below < 0) {
    fwd = reach[j], at = low[j];
    return true;
  }
  const int k = below;
  if (roller.tapered() || (k ^ 1) == j || !(a(j, low[k]) < a(k, low[k]) - margin)) return false;
  Vec3 m = n[j] - n[k];
  const double mn = norm(m);
  if (!(mn > 0)) return false;
  m = m / mn;
  const double hd = (d[j] - d[k]) / mn;  // H: m.x = hd
  const Vec3& u = roller.axis;
  const double mu = dot(m, u);
  if (!(std::fabs(mu) > 1e-3)) return false;
  const Vec3 em = cross(u, m);
  const double en = norm(em);
  if (!(en > 1e-3)) return false;
  const Vec3 e = em / en, w = cross(u, e);
  const double sc = (hd - dot(m, roller.base)) / mu;  // the axis point in H
  const Vec3 c = roller.base + u * sc;
  const Vec3 A = e * roller.radius, B = (w - u * (dot(m, w) / mu)) * roller.radius;
  const double na = dot(n[j], A), nb = dot(n[j], B), r = std::hypot(na, nb);
  if (!(r > 0)) return false;
  const double ct = -na / r, st = -nb / r;
  const double along = sc - roller.radius * st * dot(m, w) / mu;  // the point's axial coordinate
  if (!(along > margin && along < roller.height - margin)) return false;
  const Vec3 x = c + A * ct + B * st;
  const double f = std::min(a(j, x), a(k, x));
  for (int l = 0; l < 6; ++l)
    if (l != j && l != k && !(a(l, x) > f + margin)) return false;
  fwd = f, at = x;
  return true;
}

}  // namespace

/// Two-sided S of a roller and a cage web (ring_two_sided.h): `rev` = web_distance's value (the
/// web's deepest point in the roller, <= 0 here), fwd = deepest_in_web (the roller's deepest point
/// in the convex web). fwd <= min over the faces j of D_j = d_j - min over the roller of n_j.x (the
/// roller's reach past face j): when -rev already reaches that bound, S = rev with no search.
WebValue two_sided_web(const Cylinder& roller, const CageWeb& web, const Transform& pose, const WebValue& rev) {
  std::array<Vec3, 6> n;
  std::array<double, 6> d{};
  double bound = std::numeric_limits<double>::infinity();
  for (int j = 0; j < 6; ++j) {
    n[j] = pose.rotate(web.normals[j]);
    d[j] = web.offsets[j] + dot(n[j], pose.t);
    const double cu = std::clamp(dot(n[j], roller.axis), -1.0, 1.0), s = std::sqrt(std::max(0.0, 1 - cu * cu));
    const double support = std::min(dot(n[j], roller.base) - roller.radius * s, dot(n[j], roller.top_center()) - roller.top() * s);
    bound = std::min(bound, d[j] - support);
  }
  if (-rev.distance >= bound) return rev;
  double fwd;
  Vec3 x;
  if (!deepest_closed_form(roller, n, d, fwd, x)) std::tie(fwd, x) = deepest_in_web(roller, n, d);
  if (!(fwd > -rev.distance)) return rev;
  // the roller's point at depth fwd in the web, and the web boundary point nearest it (its face)
  WebValue out;
  out.distance = -fwd;
  out.point_a = x;
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j < 6; ++j)
    if (const double gap = d[j] - dot(n[j], x); gap < best) best = gap, out.point_b = x + n[j] * gap;
  return out;
}

}  // namespace interfere::bearing::detail
