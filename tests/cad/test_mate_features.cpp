// Issue #29, item 4: mates inferred from an assembly's geometry pick the assembly features to protect
// without a hand-written process file (PipelineOptions::mates, `interfere simplify --mates auto`),
// and every zero-clearance fit is a contact of assembly-clash whatever the tessellation.
// Oracles: the generated bolted joint's construction (write_bolted_test_assembly: which instance
// sits in which, which faces meet), its faces found by their own geometry (surface type, radius,
// height of their triangles), and the CAx-IF AS1 assembly's product structure (paths; skipped when
// ../shared/data is absent).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "cad_test_util.h"
#include "interfere/cad/assembly_clash.h"
#include "interfere/cad/assembly_simplify.h"
#include "interfere/cad/mates.h"
#include "interfere/cad/model.h"
#include "interfere/cad/pipeline.h"
#include "interfere/simplify/budget.h"

namespace interfere::cad {
namespace {

std::filesystem::path dir() { return testing::scratch_dir("interfere_mate_feature_tests"); }

std::filesystem::path bolted(double gap = 0) {
  const auto f = dir() / ("bolted_" + std::to_string(gap) + ".step");
  if (!std::filesystem::exists(f)) EXPECT_TRUE(write_bolted_test_assembly(f, gap).ok());
  return f;
}

const Part& part_named(const CadModel& m, const std::string& name) {
  for (const Part& p : m.parts)
    if (p.name == name) return p;
  ADD_FAILURE() << "no part " << name;
  return m.parts.front();
}

// Faces of a part by their own geometry: surface type, radius (cylinders), sense, and the mean z
// of their triangles' corners (part coordinates; the joint's parts are only moved along x).
struct FaceInfo {
  SurfaceType type;
  double radius, z;
  bool hole;
  Vec3 normal;
};
std::map<std::uint32_t, FaceInfo> face_info(const Part& p) {
  std::map<std::uint32_t, std::pair<double, int>> zsum;
  for (std::size_t t = 0; t < p.mesh.num_triangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      auto& [s, n] = zsum[p.face_ids[t]];
      s += p.mesh.positions[p.mesh.triangles[t][c]].z, ++n;
    }
  std::map<std::uint32_t, FaceInfo> out;
  for (const auto& [f, sn] : zsum) {
    const AagNode& n = p.aag.nodes[f];
    out[f] = {n.type, n.radius, sn.first / sn.second, n.hole, n.normal};
  }
  return out;
}
// The faces of `p` for which pred holds.
template <class Pred>
std::set<std::uint32_t> faces_where(const Part& p, Pred pred) {
  std::set<std::uint32_t> out;
  for (const auto& [f, i] : face_info(p))
    if (pred(i)) out.insert(f);
  return out;
}

const PreparedPart* prepared_part(const Prepared& prep, const std::string& name) {
  for (const PreparedPart& p : prep.parts)
    if (p.name == name) return &p;
  return nullptr;
}

TEST(MateFeatures, BoltedJointMatesAreTheConstructions) {
  auto m = import_step(bolted());
  ASSERT_TRUE(m.has_value()) << m.error().message();
  ASSERT_EQ(m->instances.size(), 6u);
  auto lib = default_feature_library();
  ASSERT_TRUE(lib.has_value());
  std::multiset<std::string> got;
  for (const Mate& x : infer_mates(*m, *lib)) {
    const std::string a = m->instances[x.instance_a].name, b = m->instances[x.instance_b].name;
    if (x.kind == Mate::Kind::insertion) got.insert(b + " in " + a + " (" + x.constraint + ")");
    else got.insert("contact " + std::min(a, b) + "-" + std::max(a, b));
  }
  // By construction: each bolt through the cover, the plate and its nut (through holes: bolt
  // connections); its head on the cover, its nut under the plate, the cover on the plate.
  const std::multiset<std::string> expected{
      "bolt_1 in cover (bolt)", "bolt_1 in plate (bolt)", "bolt_1 in nut_1 (bolt)",
      "bolt_2 in cover (bolt)", "bolt_2 in plate (bolt)", "bolt_2 in nut_2 (bolt)",
      "contact bolt_1-cover",   "contact bolt_2-cover",   "contact nut_1-plate",
      "contact nut_2-plate",    "contact cover-plate"};
  EXPECT_EQ(got, expected);
}

TEST(MateFeatures, MatesPickTheFeaturesWithoutAProcessFile) {
  const auto file = bolted();
  PipelineOptions o;
  o.mates = true;
  auto prep = prepare_for_simplify(file.string(), o);
  ASSERT_TRUE(prep.has_value()) << prep.error().message();
  auto m = import_step(file);
  ASSERT_TRUE(m.has_value());
  const auto near = [](double a, double b) { return std::abs(a - b) < 1e-6; };
  const auto feature_set = [&](const std::string& name) {
    const PreparedPart* p = prepared_part(*prep, name);
    EXPECT_NE(p, nullptr) << name;
    return p ? std::set<std::uint32_t>(p->feature_faces.begin(), p->feature_faces.end()) : std::set<std::uint32_t>{};
  };
  const auto includes = [](const std::set<std::uint32_t>& a, const std::set<std::uint32_t>& b) {
    return !b.empty() && std::includes(a.begin(), a.end(), b.begin(), b.end());
  };
  const auto disjoint = [](const std::set<std::uint32_t>& a, const std::set<std::uint32_t>& b) {
    return std::none_of(b.begin(), b.end(), [&](std::uint32_t f) { return a.count(f); });
  };
  // Plate and cover: the hole walls (bores of radius 4) are kept; the plate's bottom, under the
  // nuts, is larger than their seats and kept as annuli only; the side faces never.
  for (const char* name : {"plate", "cover"}) {
    const Part& part = part_named(*m, name);
    const auto kept = feature_set(name);
    EXPECT_TRUE(includes(kept, faces_where(part, [&](const FaceInfo& i) {
                  return i.type == SurfaceType::cylinder && i.hole && near(i.radius, 4);
                }))) << name;
    EXPECT_TRUE(disjoint(kept, faces_where(part, [&](const FaceInfo& i) {
                  return i.type == SurfaceType::plane && std::abs(i.normal.z) < 0.5;
                }))) << name;
  }
  EXPECT_TRUE(disjoint(feature_set("plate"), faces_where(part_named(*m, "plate"), [&](const FaceInfo& i) {
                         return i.type == SurfaceType::plane && i.normal.z < -0.5;
                       })));
  const PreparedPart* plate = prepared_part(*prep, "plate");
  ASSERT_NE(plate, nullptr);
  EXPECT_FALSE(plate->feature_triangles.empty() && plate->feature_faces.empty());
  // Bolt: the shank (boss r = 4) and the head's seat on the cover; not the head's top or side.
  const Part& bolt = part_named(*m, "bolt");
  const auto bolt_kept = feature_set("bolt");
  EXPECT_TRUE(includes(bolt_kept, faces_where(bolt, [&](const FaceInfo& i) {
                return i.type == SurfaceType::cylinder && !i.hole && near(i.radius, 4);
              })));
  EXPECT_TRUE(includes(bolt_kept, faces_where(bolt, [&](const FaceInfo& i) {
                return i.type == SurfaceType::plane && i.normal.z < -0.5 && near(i.z, 16);
              })));
  EXPECT_TRUE(disjoint(bolt_kept, faces_where(bolt, [&](const FaceInfo& i) {
                return (i.type == SurfaceType::cylinder && near(i.radius, 7)) || (i.type == SurfaceType::plane && i.normal.z > 0.5);
              })));
  // Nut: its bore and its seat on the plate (z = 0).
  const Part& nut = part_named(*m, "nut");
  const auto nut_kept = feature_set("nut");
  EXPECT_TRUE(includes(nut_kept, faces_where(nut, [&](const FaceInfo& i) {
                return (i.type == SurfaceType::cylinder && i.hole && near(i.radius, 4)) ||
                       (i.type == SurfaceType::plane && i.normal.z > 0.5 && near(i.z, 0));
              })));
  // The report says where the features come from and lists the mates.
  EXPECT_NE(prep->report_json.find("\"features_from\":\"mates\""), std::string::npos);
  EXPECT_NE(prep->report_json.find("\"constraint\":\"bolt\""), std::string::npos);
  // Simplified with the features locked: every kept face keeps its triangles, on every part.
  SimplifyOptions so;
  so.ratio = 0.3;
  so.feature_mode = FeatureMode::lock;
  so.measure_error = false;
  auto r = simplify_assembly(*prep, so);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  for (std::size_t i = 0; i < prep->parts.size(); ++i) {
    const PreparedPart& p = prep->parts[i];
    for (std::uint32_t f : p.feature_faces)
      EXPECT_EQ(std::count(r->parts[i].face_ids.begin(), r->parts[i].face_ids.end(), f),
                std::count(p.face_ids.begin(), p.face_ids.end(), f))
          << p.name << " face " << f;
  }
  // Off (no process, no mates): nothing is kept.
  auto none = prepare_for_simplify(file.string(), PipelineOptions{});
  ASSERT_TRUE(none.has_value());
  EXPECT_TRUE(none->feature_faces.empty());
  EXPECT_NE(none->report_json.find("\"features_from\":\"none\""), std::string::npos);
}

TEST(MateFeatures, ApartPartsKeepNothingAndAProcessOverridesTheMates) {
  const auto apart = dir() / "apart.step";
  ASSERT_TRUE(write_test_assembly(apart).ok());
  PipelineOptions o;
  o.mates = true;
  auto prep = prepare_for_simplify(apart.string(), o);
  ASSERT_TRUE(prep.has_value()) << prep.error().message();
  EXPECT_TRUE(prep->feature_faces.empty());
  EXPECT_NE(prep->report_json.find("\"mates\":[]"), std::string::npos);
  // With a process the step decides (a step naming only the cover keeps nothing on the bolts).
  const auto process = dir() / "cover_only.json";
  std::ofstream(process) << R"({"steps":[{"id":"P1","parts":["cover"],"constraint":"bolt"}]})";
  o.process_file = process.string(), o.step = "P1";
  auto stepped = prepare_for_simplify(bolted().string(), o);
  ASSERT_TRUE(stepped.has_value()) << stepped.error().message();
  for (const PreparedPart& p : stepped->parts)
    if (p.name != "cover") EXPECT_TRUE(p.feature_faces.empty()) << p.name;
  EXPECT_NE(stepped->report_json.find("\"features_from\":\"process\""), std::string::npos);
}

// The kind of an AS1 instance from its part's name, any case.
std::string as1_kind(const CadModel& m, std::uint32_t instance) {
  std::string name = m.parts[m.instances[instance].part].name;
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const char* k : {"bolt", "nut", "rod", "plate", "bracket"})
    if (name.find(k) != std::string::npos) return k;
  return "?";
}

std::filesystem::path shared_step(const char* file) {
  return std::filesystem::path(INTERFERE_SOURCE_DIR) / ".." / "shared" / "data" / "step" / file;
}

TEST(MateFeatures, As1MatesProtectEveryMatingPart) {
  const auto f = shared_step("as1-oc-214.stp");
  if (!std::filesystem::exists(f)) GTEST_SKIP() << f << " absent";
  auto m = import_step(f);
  ASSERT_TRUE(m.has_value());
  auto lib = default_feature_library();
  auto rules = default_semantic_rules(*lib);
  ASSERT_TRUE(rules.has_value());
  const MateSelection sel = select_mate_features(*m, *lib, *rules);
  // Every instance of AS1 takes part in a mate, and every part has faces to keep: the plate and
  // brackets their holes' walls (bores of a bolt's or the rod's radius), the bolts and the rod
  // their shanks, the nuts their bores.
  for (std::size_t k = 0; k < m->instances.size(); ++k) EXPECT_TRUE(sel.instances[k]) << m->instances[k].path;
  for (std::size_t i = 0; i < m->parts.size(); ++i) {
    const Part& p = m->parts[i];
    std::set<double> inserted;  // radii of the cylinders inserted anywhere
    for (const Mate& x : sel.mates)
      if (x.kind == Mate::Kind::insertion) inserted.insert(x.radius);
    std::size_t walls = 0;
    for (std::uint32_t f : sel.parts[i].faces) {
      const AagNode& n = p.aag.nodes[f];
      walls += n.type == SurfaceType::cylinder &&
               std::any_of(inserted.begin(), inserted.end(), [&](double r) { return std::abs(r - n.radius) < 1e-6 * r; });
    }
    EXPECT_GT(walls, 0u) << p.name;
  }
  PipelineOptions o;
  o.mates = true;
  auto prep = prepare_for_simplify(*m, o);
  ASSERT_TRUE(prep.has_value()) << prep.error().message();
  for (const PreparedPart& p : prep->parts) EXPECT_FALSE(p.feature_faces.empty()) << p.name;
}

// Issue #29, item 4: zero-clearance fits are contacts from the B-Rep, whatever the tessellation.
// The joint's meeting pairs by construction: each bolt with the plate, the cover and its nut, each
// nut with the plate, the cover with the plate.
std::set<std::string> joint_contacts() {
  return {"bolt_1|cover", "bolt_1|plate", "bolt_1|nut_1", "bolt_2|cover", "bolt_2|plate",
          "bolt_2|nut_2",   "nut_1|plate",  "nut_2|plate", "cover|plate"};
}
std::string pair_key(const CadModel& m, const InstancePairResult& p) {
  const std::string a = m.instances[p.a].name, b = m.instances[p.b].name;
  return std::min(a, b) + "|" + std::max(a, b);
}

TEST(MateFeatures, ZeroClearanceFitsAreContactsWhateverTheTessellation) {
  for (double gap : {0.0, 1e-6}) {  // the cover a hair above the plate (within 1e-7 of the size): its tessellation does not touch
    for (auto [linear, angular] : {std::pair{0.0, 0.5}, std::pair{0.01, 0.1}, std::pair{0.5, 1.0}, std::pair{2.0, 1.5}}) {
      auto m = import_step(bolted(gap), {.linear_deflection = linear, .angular_deflection = angular});
      ASSERT_TRUE(m.has_value()) << m.error().message();
      const AssemblyClashResult r = assembly_clash(*m);
      std::set<std::string> got;
      for (const InstancePairResult& p : r.pairs) {
        EXPECT_EQ(p.meeting, InstanceMeeting::contact) << pair_key(*m, p) << " gap " << gap << " ld " << linear;
        got.insert(pair_key(*m, p));
        if (gap > 0 && pair_key(*m, p) == "cover|plate") {
          EXPECT_TRUE(p.zero_clearance_fit);
          EXPECT_EQ(p.cross_pairs + p.touch_pairs, 0u);
        }
      }
      EXPECT_EQ(got, joint_contacts()) << "gap " << gap << " linear deflection " << linear;
      EXPECT_EQ(r.contacts, joint_contacts().size());
      EXPECT_EQ(r.verdict, Verdict::contact);
    }
  }
  // 0.01 mm apart is a gap, not a fit: no pair, or a clearance pair when a clearance is asked for.
  auto m = import_step(bolted(0.01));
  ASSERT_TRUE(m.has_value());
  for (const InstancePairResult& p : assembly_clash(*m).pairs) EXPECT_NE(pair_key(*m, p), "cover|plate");
  bool seen = false;
  for (const InstancePairResult& p : assembly_clash(*m, {.clearance = 0.1}).pairs)
    if (pair_key(*m, p) == "cover|plate") {
      seen = true;
      EXPECT_EQ(p.meeting, InstanceMeeting::clearance);
      EXPECT_FALSE(p.zero_clearance_fit);
    }
  EXPECT_TRUE(seen);
}

TEST(MateFeatures, As1EveryFitIsAContactWithItsOwnPaths) {
  std::size_t checked = 0;
  for (const char* file : {"as1-oc-214.stp", "as1_pe_203.stp"}) {
    if (!std::filesystem::exists(shared_step(file))) continue;
    for (double linear : {0.0, 1.0}) {
      auto m = import_step(shared_step(file), {.linear_deflection = linear});
      ASSERT_TRUE(m.has_value());
      ++checked;
      std::set<std::string> contacts_without_clearance;
      for (double clearance : {0.0, 0.5}) {
        const AssemblyClashResult r = assembly_clash(*m, {.clearance = clearance, .depth_bound_splits = 0});
        // The oracle: AS1's product structure. A bolt and the nut of its nut-bolt assembly, a bolt
        // and its bracket (same l-bracket assembly), a bolt and the plate, a nut of a bolt and the
        // plate, the rod and its nuts, the rod and each bracket, each bracket and the plate, each
        // rod nut and one bracket: 32 pairs, each named by its own two paths.
        std::map<std::string, std::size_t> kinds;
        std::set<std::string> names;
        for (const InstancePairResult& p : r.pairs) {
          const std::string pa = m->instances[p.a].path, pb = m->instances[p.b].path;
          if (clearance == 0) EXPECT_EQ(p.meeting, InstanceMeeting::contact) << file << ": " << pa << " x " << pb;
          if (p.meeting != InstanceMeeting::contact) continue;
          EXPECT_NE(pa, pb);
          EXPECT_TRUE(names.insert(std::min(pa, pb) + " x " + std::max(pa, pb)).second) << pa << " x " << pb;
          std::string a = as1_kind(*m, p.a), b = as1_kind(*m, p.b);
          if (b < a) std::swap(a, b);
          const auto parent = [](const std::string& path, int up) {
            std::string s = path;
            for (int i = 0; i < up; ++i) s = s.substr(0, s.rfind('/'));
            return s;
          };
          if (a == "bolt" && b == "nut") EXPECT_EQ(parent(pa, 1), parent(pb, 1)) << pa << " x " << pb;
          if (a == "bolt" && b == "bracket") {
            const bool a_is_bolt = as1_kind(*m, p.a) == "bolt";
            EXPECT_EQ(parent(a_is_bolt ? pa : pb, 2), parent(a_is_bolt ? pb : pa, 1)) << pa << " x " << pb;
          }
          ++kinds[a + "-" + b];
        }
        const std::map<std::string, std::size_t> expected{{"bolt-nut", 6},      {"bolt-bracket", 6}, {"bolt-plate", 6},
                                                          {"nut-plate", 6},     {"nut-rod", 2},      {"bracket-rod", 2},
                                                          {"bracket-plate", 2}, {"bracket-nut", 2}};
        EXPECT_EQ(kinds, expected) << file << " linear deflection " << linear << " clearance " << clearance;
        EXPECT_EQ(r.contacts, 32u) << file << " linear deflection " << linear << " clearance " << clearance;
        if (clearance == 0) contacts_without_clearance = names;
        else EXPECT_EQ(names, contacts_without_clearance) << file;
      }
    }
  }
  if (checked == 0) GTEST_SKIP() << "AS1 files not present";
}

// Issue #29, bad input: a process naming parts the assembly does not contain, and a renderer cap
// below the step's feature triangles, give messages naming the entity.
TEST(MateFeatures, BadInputNamesThePartAndTheCap) {
  const auto process = dir() / "misspelt.json";
  std::ofstream(process) << R"({"steps":[{"id":"P1","parts":["cover","bolts"],"constraint":"bolt"}]})";
  PipelineOptions o;
  o.process_file = process.string(), o.step = "P1";
  auto prep = prepare_for_simplify(bolted().string(), o);
  ASSERT_TRUE(prep.has_value()) << prep.error().message();
  bool named = false;
  for (const std::string& w : prep->warnings)
    named = named || (w.find("'bolts'") != std::string::npos && w.find("'P1'") != std::string::npos &&
                      w.find("'bolt'") != std::string::npos);  // the step, the part, the parts there are
  EXPECT_TRUE(named);
  // The cap: half the mates' feature triangles of the joint.
  PipelineOptions m;
  m.mates = true;
  auto joint = prepare_for_simplify(bolted().string(), m);
  ASSERT_TRUE(joint.has_value());
  std::size_t features = 0;
  for (const PreparedPart& p : joint->parts)
    features += p.instances * count_feature_triangles(p.face_ids, p.feature_faces, p.feature_triangles);
  const std::size_t cap = features / 2;
  ASSERT_GT(cap, 100u);
  SimplifyOptions so;
  so.target_triangles = cap;
  so.measure_error = false;
  auto r = simplify_assembly(*joint, so);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  EXPECT_TRUE(r->features_exceed_budget);
  EXPECT_LE(r->merged.mesh.num_triangles(), cap);
  bool capped = false;
  for (const std::string& w : r->merged.warnings)
    capped = capped || (w.find("exceed the total budget " + std::to_string(cap)) != std::string::npos &&
                      w.find("'bolt' (") != std::string::npos && w.find("'plate' (") != std::string::npos);
  EXPECT_TRUE(capped) << ::testing::PrintToString(r->merged.warnings);
}

}  // namespace
}  // namespace interfere::cad
