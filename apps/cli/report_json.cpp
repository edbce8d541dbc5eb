#include "report_json.h"

namespace interfere::cli {

nlohmann::json vec_json(const Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

nlohmann::json box_json(const Aabb& b) { return {{"min", vec_json(b.lo)}, {"max", vec_json(b.hi)}}; }

const char* kind_name(ContactKind k) {
  switch (k) {
    case ContactKind::cross: return "cross";
    case ContactKind::touch: return "touch";
    case ContactKind::none: break;
  }
  return "none";
}

nlohmann::json clash_result_json(const ClashResult& r, std::size_t max_clearance_pairs) {
  nlohmann::json regions = nlohmann::json::array();
  for (std::size_t i = 0; i < r.regions.size(); ++i) {
    const ClashRegion& g = r.regions[i];
    nlohmann::json curves = nlohmann::json::array();
    for (const Polyline& c : g.curves) {
      nlohmann::json pts = nlohmann::json::array();
      for (const Vec3& p : c.points) pts.push_back(vec_json(p));
      curves.push_back({{"closed", c.closed}, {"length", c.length}, {"points", pts}});
    }
    regions.push_back({{"id", i},
                       {"triangle_count_a", g.triangles_a.size()},
                       {"triangle_count_b", g.triangles_b.size()},
                       {"triangles_a", g.triangles_a},
                       {"triangles_b", g.triangles_b},
                       {"cross_pairs", g.cross_pairs},
                       {"touch_pairs", g.touch_pairs},
                       {"bbox", box_json(g.box)},
                       {"curve_length", g.curve_length},
                       {"curves", curves}});
  }
  double min_clearance = -1;
  nlohmann::json near = nlohmann::json::array();
  for (const ClearancePair& c : r.clearance) {
    if (min_clearance < 0 || c.distance < min_clearance) min_clearance = c.distance;
    if (near.size() < max_clearance_pairs) {
      near.push_back({{"a", c.a}, {"b", c.b}, {"distance", c.distance},
                      {"point_a", vec_json(c.point_a)}, {"point_b", vec_json(c.point_b)}});
    }
  }
  double total_curve = 0;
  for (const ClashRegion& g : r.regions) total_curve += g.curve_length;
  return {{"verdict", verdict_name(r.verdict)},
          {"verdict_reasons", r.verdict_reasons},
          {"interference", r.interference()},
          {"pairs", r.pairs.size()},
          {"cross_pairs", r.cross_pairs},
          {"touch_pairs", r.touch_pairs},
          {"candidate_pairs", r.candidate_pairs},
          {"containment", containment_name(r.containment)},
          {"touching_overlap", r.touching_overlap},
          {"region_count", r.regions.size()},
          {"curve_length", total_curve},
          {"regions", regions},
          {"clearance",
           {{"pairs", r.clearance.size()},
            {"min_distance", min_clearance < 0 ? nlohmann::json(nullptr) : nlohmann::json(min_clearance)},
            {"list", near},
            {"list_truncated", r.clearance.size() > near.size()}}}};
}

nlohmann::json distance_result_json(const DistanceResult& r) {
  return {{"intersecting", r.intersecting},
          {"distance", std::isfinite(r.distance) ? nlohmann::json(r.distance) : nlohmann::json(nullptr)},
          {"point_a", vec_json(r.point_a)},
          {"point_b", vec_json(r.point_b)},
          {"triangle_a", r.triangle_a},
          {"triangle_b", r.triangle_b}};
}

}  // namespace interfere::cli
