// Feature recognition on the AAG (issue #6, item 3), after He & Xu (SJTU 2023) §2.2 and Joshi &
// Chang (CAD 1988): minimal AAGs by splitting at inner loops and then at convex arcs; patterns from
// a JSON library matched by backtracking attributed subgraph isomorphism (Ullmann 1976 without the
// refinement matrix: candidates of a pattern node come from the neighbours of an already matched
// node), then geometric checks. Patterns are tried by decreasing priority; the faces a match owns
// are claimed so that a smaller pattern does not re-use them (a counterbore's bore is not also a
// through hole).
#include "interfere/cad/features.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "data_dir.h"
#include "aag_merge.h"
#include "hole_recognition.h"
#include "pocket_recognition.h"

namespace interfere::cad {
namespace {

using json = nlohmann::json;

bool parse_surface(const std::string& s, SurfaceType& t) {
  static const std::pair<const char*, SurfaceType> names[] = {
      {"plane", SurfaceType::plane}, {"cylinder", SurfaceType::cylinder}, {"cone", SurfaceType::cone},
      {"sphere", SurfaceType::sphere}, {"torus", SurfaceType::torus}, {"bspline", SurfaceType::bspline},
      {"other", SurfaceType::other}};
  for (const auto& [n, v] : names)
    if (s == n) return t = v, true;
  return false;
}
bool parse_curve(const std::string& s, CurveType& t) {
  static const std::pair<const char*, CurveType> names[] = {
      {"line", CurveType::line}, {"circle", CurveType::circle}, {"ellipse", CurveType::ellipse}, {"other", CurveType::other}};
  for (const auto& [n, v] : names)
    if (s == n) return t = v, true;
  return false;
}
bool parse_convexity(const std::string& s, Convexity& c) {
  if (s == "convex") return c = Convexity::convex, true;
  if (s == "concave") return c = Convexity::concave, true;
  if (s == "smooth") return c = Convexity::smooth, true;
  return false;
}

struct Ctx {
  const Aag& g;
  double tol;
  std::vector<std::vector<std::uint32_t>> arcs_of;  // node -> arc indices
  std::vector<int> concave, convex;
  std::vector<double> span;  // cylinder/cone: summed angular spans of the node's faces (split faces merged)
};

bool node_ok(const Ctx& c, const PatternNode& pn, std::uint32_t n) {
  const AagNode& node = c.g.nodes[n];
  if (std::find(pn.types.begin(), pn.types.end(), node.type) == pn.types.end()) return false;
  if (pn.hole >= 0 && int(node.hole) != pn.hole) return false;
  if (pn.concave_arcs >= 0 && c.concave[n] != pn.concave_arcs) return false;
  if (pn.convex_arcs >= 0 && c.convex[n] != pn.convex_arcs) return false;
  if (pn.min_convex_arcs >= 0 && c.convex[n] < pn.min_convex_arcs) return false;
  return true;
}

bool arc_ok(const Ctx& c, const PatternArc& pa, std::uint32_t x, std::uint32_t y) {
  for (std::uint32_t ai : c.arcs_of[x]) {
    const AagArc& a = c.g.arcs[ai];
    if (!((a.a == x && a.b == y) || (a.a == y && a.b == x))) continue;
    if (!pa.curves.empty() && std::find(pa.curves.begin(), pa.curves.end(), a.curve) == pa.curves.end()) continue;
    if (!pa.convexity.empty() && std::find(pa.convexity.begin(), pa.convexity.end(), a.convexity) == pa.convexity.end())
      continue;
    return true;
  }
  return false;
}

bool axial(const AagNode& n) {
  return n.type == SurfaceType::cylinder || n.type == SurfaceType::cone || n.type == SurfaceType::torus;
}

bool check_ok(const Ctx& c, const PatternCheck& ck, const std::vector<std::uint32_t>& nodes) {
  auto N = [&](std::size_t i) -> const AagNode& { return c.g.nodes[nodes[i]]; };
  const double tol = c.tol;
  if (ck.kind == "coaxial") {
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      const AagNode &a = N(0), &b = N(i);
      if (!axial(a) || !axial(b)) return false;
      if (norm(cross(a.axis, b.axis)) > tol) return false;
      const Vec3 d = b.axis_point - a.axis_point;
      const double off = norm(d - a.axis * dot(d, a.axis));
      if (off > tol * std::max({1.0, a.radius, b.radius})) return false;
    }
    return true;
  }
  if (ck.kind == "radius_less") {
    for (std::size_t i = 1; i < nodes.size(); ++i)
      if (!(N(i - 1).radius < N(i).radius * (1 - tol))) return false;
    return true;
  }
  if (ck.kind == "perpendicular_to_axis") {  // plane, then an axial face
    const AagNode &p = N(0), &a = N(1);
    return p.type == SurfaceType::plane && axial(a) && std::abs(std::abs(dot(p.normal, a.axis)) - 1) <= tol;
  }
  if (ck.kind == "parallel_planes") return std::abs(std::abs(dot(N(0).normal, N(1).normal)) - 1) <= tol;
  if (ck.kind == "opposite_normals") return dot(N(0).normal, N(1).normal) <= -1 + tol;
  if (ck.kind == "perpendicular_planes") return std::abs(dot(N(0).normal, N(1).normal)) <= tol;
  if (ck.kind == "full_circle") {
    // Issue #29: a boss's wall goes all round; convex fillets and corner rounds (quarter arcs) do not.
    for (std::uint32_t n : nodes)
      if (!(c.span[n] >= 2 * M_PI - 0.02)) return false;
    return true;
  }
  return false;
}

void match(const Ctx& c, const FeaturePattern& p, std::vector<std::uint32_t>& map, std::vector<char>& used,
           std::vector<std::vector<std::uint32_t>>& out) {
  const std::size_t k = map.size();
  if (k == p.nodes.size()) {
    for (const PatternCheck& ck : p.checks) {
      std::vector<std::uint32_t> nodes;
      for (const std::string& r : ck.roles)
        for (std::size_t i = 0; i < p.nodes.size(); ++i)
          if (p.nodes[i].role == r) nodes.push_back(map[i]);
      if (!check_ok(c, ck, nodes)) return;
    }
    out.push_back(map);
    return;
  }
  // Candidates: neighbours of a matched node linked to node k by a pattern arc, else all nodes.
  std::vector<std::uint32_t> cand;
  bool linked = false;
  for (const PatternArc& pa : p.arcs) {
    std::size_t other = p.nodes.size();
    for (std::size_t i = 0; i < k; ++i) {
      if ((pa.a == p.nodes[k].role && pa.b == p.nodes[i].role) || (pa.b == p.nodes[k].role && pa.a == p.nodes[i].role))
        other = i;
    }
    if (other == p.nodes.size()) continue;
    linked = true;
    for (std::uint32_t ai : c.arcs_of[map[other]]) {
      const AagArc& a = c.g.arcs[ai];
      cand.push_back(a.a == map[other] ? a.b : a.a);
    }
    break;
  }
  if (!linked)
    for (std::uint32_t n = 0; n < c.g.nodes.size(); ++n) cand.push_back(n);
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  for (std::uint32_t n : cand) {
    if (used[n] || !node_ok(c, p.nodes[k], n)) continue;
    bool ok = true;
    for (const PatternArc& pa : p.arcs) {
      for (std::size_t i = 0; i < k && ok; ++i) {
        if (pa.a == p.nodes[k].role && pa.b == p.nodes[i].role) ok = arc_ok(c, pa, n, map[i]);
        else if (pa.b == p.nodes[k].role && pa.a == p.nodes[i].role) ok = arc_ok(c, pa, map[i], n);
      }
    }
    if (!ok) continue;
    used[n] = 1;
    map.push_back(n);
    match(c, p, map, used, out);
    map.pop_back();
    used[n] = 0;
  }
}

}  // namespace

bool FeatureLibrary::has(const std::string& type) const {
  return std::any_of(patterns.begin(), patterns.end(), [&](const FeaturePattern& p) { return p.type == type; });
}

std::vector<std::string> FeatureLibrary::roles(const std::string& type) const {
  std::vector<std::string> out;
  for (const FeaturePattern& p : patterns)
    if (p.type == type)
      for (const PatternNode& n : p.nodes)
        if (std::find(out.begin(), out.end(), n.role) == out.end()) out.push_back(n.role);
  return out;
}

Expected<FeatureLibrary> parse_feature_library(const std::string& text, const std::string& source) {
  FeatureLibrary lib;
  auto fail = [&](const std::string& what) { return Error{.file = source, .reason = what}; };
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    return fail(std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("patterns") || !j["patterns"].is_array())
    return fail("a feature library is an object with a \"patterns\" array");
  try {
    for (const json& jp : j["patterns"]) {
      FeaturePattern p;
      p.type = jp.at("type").get<std::string>();
      const std::string where = "pattern '" + p.type + "': ";
      p.priority = jp.value("priority", 0);
      for (const json& jn : jp.at("nodes")) {
        PatternNode n;
        n.role = jn.at("role").get<std::string>();
        if (std::any_of(p.nodes.begin(), p.nodes.end(), [&](const PatternNode& o) { return o.role == n.role; }))
          return fail(where + "role '" + n.role + "' appears twice");
        for (const json& t : jn.at("types")) {
          SurfaceType st;
          if (!parse_surface(t.get<std::string>(), st)) return fail(where + "unknown surface type '" + t.get<std::string>() + "'");
          n.types.push_back(st);
        }
        if (jn.contains("hole")) n.hole = jn["hole"].get<bool>() ? 1 : 0;
        n.concave_arcs = jn.value("concave_arcs", -1);
        n.convex_arcs = jn.value("convex_arcs", -1);
        n.min_convex_arcs = jn.value("min_convex_arcs", -1);
        p.nodes.push_back(n);
      }
      if (p.nodes.empty()) return fail(where + "no nodes");
      auto has_role = [&](const std::string& r) {
        return std::any_of(p.nodes.begin(), p.nodes.end(), [&](const PatternNode& n) { return n.role == r; });
      };
      for (const json& ja : jp.value("arcs", json::array())) {
        PatternArc a;
        a.a = ja.at("a").get<std::string>(), a.b = ja.at("b").get<std::string>();
        if (!has_role(a.a) || !has_role(a.b)) return fail(where + "arc between unknown roles " + a.a + ", " + a.b);
        for (const json& t : ja.value("curves", json::array())) {
          CurveType ct;
          if (!parse_curve(t.get<std::string>(), ct)) return fail(where + "unknown curve type '" + t.get<std::string>() + "'");
          a.curves.push_back(ct);
        }
        for (const json& t : ja.value("convexity", json::array())) {
          Convexity cv;
          if (!parse_convexity(t.get<std::string>(), cv)) return fail(where + "unknown convexity '" + t.get<std::string>() + "'");
          a.convexity.push_back(cv);
        }
        p.arcs.push_back(a);
      }
      static const std::set<std::string> kinds{"coaxial", "radius_less", "perpendicular_to_axis", "parallel_planes",
                                               "opposite_normals", "perpendicular_planes", "full_circle"};
      for (const json& jc : jp.value("checks", json::array())) {
        PatternCheck c;
        c.kind = jc.at("kind").get<std::string>();
        if (!kinds.count(c.kind)) return fail(where + "unknown check '" + c.kind + "'");
        c.roles = jc.at("roles").get<std::vector<std::string>>();
        for (const auto& r : c.roles)
          if (!has_role(r)) return fail(where + "check '" + c.kind + "' names unknown role '" + r + "'");
        p.checks.push_back(c);
      }
      // Shared roles (base faces) are listed; every other role is owned.
      for (const json& jn : jp.at("nodes"))
        if (jn.value("shared", false)) p.checks.push_back({"__shared", {jn.at("role").get<std::string>()}});
      lib.patterns.push_back(std::move(p));
    }
  } catch (const json::exception& e) {
    return fail(std::string("malformed pattern: ") + e.what());
  }
  std::stable_sort(lib.patterns.begin(), lib.patterns.end(),
                   [](const FeaturePattern& a, const FeaturePattern& b) { return a.priority > b.priority; });
  return lib;
}

Expected<FeatureLibrary> load_feature_library(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return Error{.file = path.string(), .reason = "cannot open the feature library"};
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_feature_library(ss.str(), path.string());
}

std::filesystem::path data_file(const std::string& name) {
  if (const char* env = std::getenv("INTERFERE_DATA_DIR")) {
    const std::filesystem::path p = std::filesystem::path(env) / "features" / name;
    if (std::filesystem::exists(p)) return p;
  }
  const std::filesystem::path installed = std::filesystem::path(INTERFERE_DATA_DIR) / "features" / name;
  if (std::filesystem::exists(installed)) return installed;
  return std::filesystem::path(INTERFERE_SOURCE_DATA_DIR) / "features" / name;
}

Expected<FeatureLibrary> default_feature_library() { return load_feature_library(data_file("library.json")); }

std::vector<std::vector<std::uint32_t>> minimal_subgraphs(const Aag& aag) {
  const std::size_t n = aag.nodes.size();
  std::vector<std::uint32_t> parent(n);
  for (std::uint32_t i = 0; i < n; ++i) parent[i] = i;
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const AagArc& a : aag.arcs) {
    if (a.inner_loop_a || a.inner_loop_b || a.convexity == Convexity::convex) continue;
    const std::uint32_t x = find(a.a), y = find(a.b);
    if (x != y) parent[std::max(x, y)] = std::min(x, y);
  }
  std::vector<std::vector<std::uint32_t>> groups(n);
  for (std::uint32_t i = 0; i < n; ++i) groups[find(i)].push_back(i);
  std::vector<std::vector<std::uint32_t>> out;
  for (auto& g : groups)
    if (!g.empty()) out.push_back(std::move(g));
  return out;
}

namespace {
bool same_surface(const AagNode& a, const AagNode& b, double tol) {
  if (a.type != b.type || a.hole != b.hole) return false;
  if (a.type == SurfaceType::plane)
    return dot(a.normal, b.normal) >= 1 - tol &&
           std::abs(dot(b.axis_point - a.axis_point, a.normal)) <= tol * std::max(1.0, norm(b.axis_point - a.axis_point));
  if (!axial(a) && a.type != SurfaceType::sphere) return false;
  const double scale = std::max({1.0, a.radius, b.radius});
  if (std::abs(a.radius - b.radius) > tol * scale) return false;
  if (a.type == SurfaceType::sphere) return norm(a.axis_point - b.axis_point) <= tol * scale;
  if (norm(cross(a.axis, b.axis)) > tol) return false;
  const Vec3 d = b.axis_point - a.axis_point;
  return norm(d - a.axis * dot(d, a.axis)) <= tol * scale;
}
}  // namespace

namespace detail {
MergedAag merge_split_faces(const Aag& input, double tolerance) {
  const std::size_t n_in = input.nodes.size();
  std::vector<std::uint32_t> parent(n_in);
  for (std::uint32_t i = 0; i < n_in; ++i) parent[i] = i;
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  const double merge_tol = std::max(tolerance, 1e-6);
  for (const AagArc& a : input.arcs)
    if (a.convexity == Convexity::smooth && same_surface(input.nodes[a.a], input.nodes[a.b], merge_tol)) {
      const std::uint32_t x = find(a.a), y = find(a.b);
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
    }
  MergedAag m;
  m.group_of.resize(n_in);
  for (std::uint32_t i = 0; i < n_in; ++i) {
    const std::uint32_t r = find(i);
    if (r == i) m.group_of[i] = static_cast<std::uint32_t>(m.rep.size()), m.rep.push_back(i), m.members.emplace_back();
  }
  for (std::uint32_t i = 0; i < n_in; ++i) m.group_of[i] = m.group_of[find(i)], m.members[m.group_of[i]].push_back(i);
  for (std::uint32_t g = 0; g < m.rep.size(); ++g) {
    m.aag.nodes.push_back(input.nodes[m.rep[g]]);
    m.aag.nodes.back().face = g;
  }
  for (const AagArc& a : input.arcs) {
    const std::uint32_t x = m.group_of[a.a], y = m.group_of[a.b];
    if (x == y) continue;
    AagArc arc = a;
    arc.a = std::min(x, y), arc.b = std::max(x, y);
    m.aag.arcs.push_back(arc);
  }
  return m;
}
}  // namespace detail

std::vector<Feature> recognize_features(const Aag& input, const FeatureLibrary& library, double tolerance) {
  // Faces split by the modeller (a hole as two half cylinders) are one surface: faces joined by a
  // smooth arc and lying on the same plane/cylinder/cone/sphere are merged into one node first; the
  // features are reported with every member face.
  detail::MergedAag merged = detail::merge_split_faces(input, tolerance);
  const Aag& aag = merged.aag;
  const std::vector<std::uint32_t>& group_of = merged.group_of;
  const std::vector<std::uint32_t>& rep = merged.rep;
  const std::vector<std::vector<std::uint32_t>>& members = merged.members;
  Ctx c{aag, tolerance, {}, {}, {}, {}};
  const std::size_t n = aag.nodes.size();
  c.arcs_of.resize(n);
  c.concave.assign(n, 0), c.convex.assign(n, 0), c.span.assign(n, 0);
  for (std::uint32_t g = 0; g < n; ++g)
    for (std::uint32_t f : members[g]) c.span[g] += input.nodes[f].arc_span;
  for (std::uint32_t i = 0; i < aag.arcs.size(); ++i) {
    const AagArc& a = aag.arcs[i];
    c.arcs_of[a.a].push_back(i), c.arcs_of[a.b].push_back(i);
    if (a.convexity == Convexity::concave) ++c.concave[a.a], ++c.concave[a.b];
    if (a.convexity == Convexity::convex) ++c.convex[a.a], ++c.convex[a.b];
  }
  std::vector<char> claimed(n, 0);
  std::vector<Feature> out;
  // Holes (issue #29): the library's hole types are recognised from the walls' geometry and their
  // ends (hole_recognition.cpp), not by matching "a concave cylinder between two planes"; their faces
  // are claimed before the other patterns run.
  std::set<std::string> hole_types;
  for (const FeaturePattern& p : library.patterns)
    if (detail::hole_types().count(p.type)) hole_types.insert(p.type);
  std::vector<Feature> holes;
  if (!hole_types.empty())
    for (detail::HoleFeature& h : detail::recognize_holes(input, hole_types)) {
      for (std::uint32_t f : h.owned) claimed[group_of[f]] = 1;
      holes.push_back(std::move(h.feature));
    }
  // Floor features (issue #29, item 1; pocket_recognition.cpp): pockets, slots, blind slots and steps,
  // a floor with walls standing on it, floor fillets between them and open sides, which patterns of
  // fixed size cannot state (walls all round, fillets of any number); claimed before the patterns too.
  std::set<std::string> floor_types;
  for (const FeaturePattern& p : library.patterns)
    if (detail::floor_feature_types().count(p.type)) floor_types.insert(p.type);
  std::vector<detail::FloorFeature> floor_list;
  if (!floor_types.empty())
    for (detail::FloorFeature& ff : detail::recognize_floor_features(aag, claimed, floor_types)) {
      claimed[ff.floor] = 1;
      for (std::uint32_t w : ff.walls) claimed[w] = 1;
      for (std::uint32_t w : ff.fillets) claimed[w] = 1;
      floor_list.push_back(std::move(ff));
    }
  for (const FeaturePattern& p : library.patterns) {
    if (hole_types.count(p.type) || floor_types.count(p.type)) continue;
    std::set<std::string> shared;
    for (const PatternCheck& ck : p.checks)
      if (ck.kind == "__shared") shared.insert(ck.roles[0]);
    FeaturePattern q = p;
    q.checks.erase(std::remove_if(q.checks.begin(), q.checks.end(), [](const PatternCheck& ck) { return ck.kind == "__shared"; }),
                   q.checks.end());
    std::vector<std::vector<std::uint32_t>> matches;
    std::vector<std::uint32_t> map;
    std::vector<char> used(n, 0);
    match(c, q, map, used, matches);
    std::set<std::vector<std::uint32_t>> seen;
    for (const auto& m : matches) {
      std::vector<std::uint32_t> owned;
      for (std::size_t i = 0; i < q.nodes.size(); ++i)
        if (!shared.count(q.nodes[i].role)) owned.push_back(m[i]);
      std::sort(owned.begin(), owned.end());
      if (seen.count(owned)) continue;
      if (std::any_of(owned.begin(), owned.end(), [&](std::uint32_t f) { return claimed[f]; })) continue;
      seen.insert(owned);
      for (std::uint32_t f : owned) claimed[f] = 1;
      Feature f;
      f.type = q.type;
      for (std::size_t i = 0; i < q.nodes.size(); ++i) {
        f.roles[q.nodes[i].role] = m[i];
        f.faces.push_back(m[i]);
        const AagNode& node = aag.nodes[m[i]];
        if (axial(node) || node.type == SurfaceType::sphere) {
          if (norm(f.axis) == 0) f.axis = node.axis, f.axis_point = node.axis_point;
          f.radii.push_back(node.radius);
        }
      }
      std::sort(f.faces.begin(), f.faces.end());
      f.faces.erase(std::unique(f.faces.begin(), f.faces.end()), f.faces.end());
      out.push_back(std::move(f));
    }
  }
  for (Feature& f : out) {
    for (auto& [role, id] : f.roles) {
      f.role_faces[role] = members[id];
      id = rep[id];
    }
    std::vector<std::uint32_t> faces;
    for (std::uint32_t g : f.faces) faces.insert(faces.end(), members[g].begin(), members[g].end());
    std::sort(faces.begin(), faces.end());
    f.faces = std::move(faces);
  }
  for (Feature& h : holes) out.push_back(std::move(h));
  for (const detail::FloorFeature& ff : floor_list) {
    Feature f;
    f.type = ff.type;
    auto add = [&](const std::string& role, const std::vector<std::uint32_t>& groups) {
      if (groups.empty()) return;
      auto& v = f.role_faces[role];
      for (std::uint32_t g : groups) v.insert(v.end(), members[g].begin(), members[g].end());
      std::sort(v.begin(), v.end());
      f.roles[role] = rep[*std::min_element(groups.begin(), groups.end(), [&](std::uint32_t a, std::uint32_t b) { return rep[a] < rep[b]; })];
    };
    add("floor", {ff.floor});
    if (ff.type == "slot" || ff.type == "blind_slot") {
      add("wall1", {ff.sides[0]}), add("wall2", {ff.sides[1]});
      add("end", ff.ends);
    } else {
      add("wall", ff.walls);
    }
    add("fillet", ff.fillets);
    for (const auto& [role, faces] : f.role_faces) f.faces.insert(f.faces.end(), faces.begin(), faces.end());
    std::sort(f.faces.begin(), f.faces.end());
    f.faces.erase(std::unique(f.faces.begin(), f.faces.end()), f.faces.end());
    out.push_back(std::move(f));
  }
  std::sort(out.begin(), out.end(), [](const Feature& a, const Feature& b) {
    return a.type != b.type ? a.type < b.type : a.faces < b.faces;
  });
  return out;
}

}  // namespace interfere::cad
