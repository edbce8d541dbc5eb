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
    Score s;
    s.truth = feats.size(), s.reported = found.size();
    std::vector<char> t_used(feats.size(), 0), f_used(found.size(), 0), t_typed(feats.size(), 0);
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t i = 0; i < feats.size(); ++i)
        for (std::size_t j = 0; j < found.size() && !t_used[i]; ++j) {
          if (f_used[j] || (pass == 0 && found[j].type != feats[i].type) || !matches(feats[i], found[j], tol)) continue;
          t_used[i] = f_used[j] = 1;
          ++s.found;
          if (found[j].type == feats[i].type) ++s.typed, t_typed[i] = 1;
        }
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
    for (std::size_t i = 0; i < feats.size(); ++i) {
      Score& b = by_type[feats[i].type];
      ++b.truth, b.found += t_used[i], b.typed += t_typed[i];
    }
    for (std::size_t j = 0; j < found.size(); ++j) ++by_type[found[j].type].reported;
    ++parts;
    total.truth += s.truth, total.reported += s.reported, total.found += s.found, total.typed += s.typed;
    std::map<std::string, int> truth_types, found_types;
    for (const auto& t : feats) ++truth_types[t.type];
    for (const auto& f : found) ++found_types[f.type];
    table.push_back({{"file", file}, {"truth", s.truth}, {"reported", s.reported}, {"found", s.found}, {"typed", s.typed},
                     {"precision", s.precision()}, {"recall", s.recall()}, {"typed_precision", s.typed_precision()},
                     {"typed_recall", s.typed_recall()}, {"truth_types", truth_types}, {"reported_types", found_types}});
    std::printf("%-34s truth %3zu reported %3zu  P %.3f R %.3f  typed P %.3f R %.3f\n", file.c_str(), s.truth, s.reported,
                s.precision(), s.recall(), s.typed_precision(), s.typed_recall());
  }
  if (parts == 0) GTEST_SKIP() << "none of the truth set's STEP files present";
  json types = json::object();
  for (const auto& [type, b] : by_type) {
    types[type] = {{"truth", b.truth}, {"reported", b.reported}, {"typed_found", b.typed}, {"found", b.found}};
    std::printf("  %-14s truth %3zu found %3zu typed %3zu reported %3zu\n", type.c_str(), b.truth, b.found, b.typed, b.reported);
  }
  std::printf("TOTAL truth %zu reported %zu P %.3f R %.3f typed P %.3f R %.3f\n", total.truth, total.reported,
              total.precision(), total.recall(), total.typed_precision(), total.typed_recall());
  // Regression floors (measured 2026-11-29: typed precision 0.88, recall 0.92 over 173 truth features;
  // after the labeller's two fixes found by rendering the labels (edge tolerance, features sharing only
  // walls: gmsh_Zylkopf -2 wrong pockets, gmsh_Block 25 -> 52 features) 0.92 / 0.83 over 198, and 0.91 /
  // 0.90 with the recognizer's same fix); the 0.95 is a hole target and is not met here on every
  // part (docs/simplify.md).
  EXPECT_GE(total.typed_precision(), 0.85);
  EXPECT_GE(total.typed_recall(), 0.85);
  if (const char* out = std::getenv("INTERFERE_FLOOR_PR_JSON")) {
    std::ofstream o(out);
    o << json{{"parts", table}, {"types", types},
              {"total", {{"truth", total.truth}, {"reported", total.reported}, {"found", total.found}, {"typed", total.typed}}}}
             .dump(1);
  }
}

}  // namespace
}  // namespace interfere::cad
