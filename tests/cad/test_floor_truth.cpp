// Pockets, slots, blind slots and steps against the real-part truth set (issue #29, item 2):
// tests/data/floor_truth/ holds, per STEP file of ../shared/data/step (NIST CTC/FTC, gmsh, CAx-IF
// AS1, trimesh), the floor features from tools/floor_truth/label_floors.cpp, an independent labeller
// (rays cast just above each planar face across its boundary against the solid, no AAG). A truth
// feature matches a recognised one (one to one, typed matches first) when one of its floor points and
// at least 80 % of its walled boundary points lie on the recognised feature's triangles. Precision and
// recall per part, of the features found and of their types; the totals must not fall below 0.85.
// Skipped when the shared data is absent. INTERFERE_FLOOR_DEBUG=1 prints the unmatched features.
// INTERFERE_FLOOR_PR_JSON=<file> writes the table (tools/floor_truth/pr_table.py puts it in
// docs/simplify.md).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "truth_set.h"
#include "interfere/cad/features.h"
#include "interfere/cad/model.h"

namespace interfere::cad {
namespace {

using json = nlohmann::json;

const std::set<std::string> kFloorTypes{"pocket", "slot", "blind_slot", "through_step"};

struct TruthFeature {
  std::string type;
  std::vector<Vec3> floor_points, walled;
};

struct Found {
  std::string type;
  std::vector<std::array<Vec3, 3>> tris;  // world
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  std::string roles;  // debug: role -> centroid of its triangles
};

// Closest point on triangle (Ericson, Real-Time Collision Detection 5.1.5), distance.
double point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return norm(p - a);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return norm(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return norm(p - (a + ab * (d1 / (d1 - d3))));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return norm(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return norm(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return norm(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double denom = 1 / (va + vb + vc);
  return norm(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

bool on(const Found& f, const Vec3& p, double tol) {
  if (p.x < f.lo.x - tol || p.y < f.lo.y - tol || p.z < f.lo.z - tol || p.x > f.hi.x + tol || p.y > f.hi.y + tol ||
      p.z > f.hi.z + tol)
    return false;
  for (const auto& t : f.tris)
    if (point_triangle(p, t[0], t[1], t[2]) <= tol) return true;
  return false;
}

bool matches(const TruthFeature& t, const Found& f, double tol) {
  if (std::none_of(t.floor_points.begin(), t.floor_points.end(), [&](const Vec3& p) { return on(f, p, tol); })) return false;
  std::size_t n = 0;
  for (const Vec3& p : t.walled) n += on(f, p, tol);
  return n >= 0.8 * double(t.walled.size());
}

using testing::Score;

std::filesystem::path step_dir() { return testing::shared_step_dir(); }

Vec3 vec(const json& a) { return {a[0].get<double>(), a[1].get<double>(), a[2].get<double>()}; }

TEST(FloorTruth, PrecisionAndRecallPerPart) {
  if (!std::filesystem::is_directory(step_dir())) GTEST_SKIP() << "../shared/data not present";
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value()) << lib.error().message();
  const std::vector<std::filesystem::path> files = testing::truth_files("floor_truth");
  ASSERT_GE(files.size(), 6u);
  json table = json::array();
  Score total;
  std::map<std::string, Score> by_type;
  std::size_t parts = 0;
  for (const auto& tf : files) {
    std::ifstream in(tf);
    const json truth = json::parse(in);
    const std::string file = truth.at("file");
    const auto step = step_dir() / file;
    if (!std::filesystem::exists(step)) continue;
    auto model = import_step(step);
    ASSERT_TRUE(model.has_value()) << file << ": " << model.error().message();
    std::vector<TruthFeature> feats;
    for (const json& s : truth.at("solids"))
      for (const json& f : s.at("features")) {
        TruthFeature t;
        t.type = f.at("type");
        for (const json& p : f.at("floor_points")) t.floor_points.push_back(vec(p));
        for (const json& p : f.at("walled")) t.walled.push_back(vec(p));
        feats.push_back(std::move(t));
      }
    std::vector<Found> found;
    double deflection = 0;
    for (const Instance& inst : model->instances) {
      const Part& part = model->parts[inst.part];
      deflection = std::max(deflection, part.tessellation_error());
      for (const Feature& f : recognize_features(part.aag, *lib)) {
        if (!kFloorTypes.count(f.type)) continue;
        Found g;
        g.type = f.type;
        for (std::size_t t = 0; t < part.mesh.num_triangles(); ++t)
          if (std::binary_search(f.faces.begin(), f.faces.end(), part.face_ids[t])) {
            std::array<Vec3, 3> tri;
            for (int k = 0; k < 3; ++k) {
              tri[k] = inst.placement.apply(part.mesh.positions[part.mesh.triangles[t][k]]);
              g.lo = {std::min(g.lo.x, tri[k].x), std::min(g.lo.y, tri[k].y), std::min(g.lo.z, tri[k].z)};
              g.hi = {std::max(g.hi.x, tri[k].x), std::max(g.hi.y, tri[k].y), std::max(g.hi.z, tri[k].z)};
            }
            g.tris.push_back(tri);
          }
        for (const auto& [role, fs] : f.role_faces) {
          Vec3 c{0, 0, 0};
          int k = 0;
          for (std::size_t t = 0; t < part.mesh.num_triangles(); ++t)
            if (std::binary_search(fs.begin(), fs.end(), part.face_ids[t]))
              for (int q = 0; q < 3; ++q) c = c + inst.placement.apply(part.mesh.positions[part.mesh.triangles[t][q]]), ++k;
          if (k) c = c / double(k);
          char b[160];
          std::snprintf(b, sizeof b, " %s(%zu)@(%.1f,%.1f,%.1f)", role.c_str(), fs.size(), c.x, c.y, c.z);
          g.roles += b;
        }
        found.push_back(std::move(g));
      }
    }
    const double tol = 2 * deflection + 1e-3;
    const testing::Matching m =
        testing::match_one_to_one(feats, found, [&](const TruthFeature& t, const Found& f) { return matches(t, f, tol); });
    const std::vector<char>& t_typed = m.truth_typed;
    const std::vector<char>& f_used = m.found_used;
    if (std::getenv("INTERFERE_FLOOR_DEBUG")) {
      for (std::size_t i = 0; i < feats.size(); ++i)
        if (!t_typed[i])
        {
          std::printf("  missed %s floor (%.3f, %.3f, %.3f) walled %zu floors %zu\n", feats[i].type.c_str(), feats[i].floor_points[0].x,
                      feats[i].floor_points[0].y, feats[i].floor_points[0].z, feats[i].walled.size(), feats[i].floor_points.size());
          for (std::size_t j = 0; j < found.size(); ++j) {
            std::size_t k = 0, fl = 0;
            for (const Vec3& q : feats[i].walled) k += on(found[j], q, tol);
            for (const Vec3& q : feats[i].floor_points) fl += on(found[j], q, tol);
            if (k || fl) std::printf("    vs found %zu %s: walled on %zu, floors on %zu\n", j, found[j].type.c_str(), k, fl);
          }
        }
      for (std::size_t j = 0; j < found.size(); ++j)
        if (!f_used[j])
          std::printf("  extra %s box (%.3f, %.3f, %.3f)-(%.3f, %.3f, %.3f)\n", found[j].type.c_str(), found[j].lo.x, found[j].lo.y,
                      found[j].lo.z, found[j].hi.x, found[j].hi.y, found[j].hi.z), std::printf("   %s\n", found[j].roles.c_str());
    }
    testing::add_part(m, feats, found, by_type, total);
    ++parts;
    std::map<std::string, int> truth_types, found_types;
    for (const auto& t : feats) ++truth_types[t.type];
    for (const auto& f : found) ++found_types[f.type];
    json row = testing::part_row(file, m.score, 34);
    row["truth_types"] = truth_types, row["reported_types"] = found_types;
    table.push_back(std::move(row));
  }
  if (parts == 0) GTEST_SKIP() << "none of the truth set's STEP files present";
  const json types = testing::type_rows(by_type, total, 14);
  // Regression floors (measured 2026-11-29: typed precision 0.88, recall 0.92 over 173 truth features;
  // after the labeller's two fixes found by rendering the labels (edge tolerance, features sharing only
  // walls: gmsh_Zylkopf -2 wrong pockets, gmsh_Block 25 -> 52 features) 0.92 / 0.83 over 198, and 0.91 /
  // 0.90 with the recognizer's same fix); the 0.95 is a hole target and is not met here on every
  // part (docs/simplify.md).
  EXPECT_GE(total.typed_precision(), 0.85);
  EXPECT_GE(total.typed_recall(), 0.85);
  testing::write_pr_json("INTERFERE_FLOOR_PR_JSON", table, types, total);
}

}  // namespace
}  // namespace interfere::cad
