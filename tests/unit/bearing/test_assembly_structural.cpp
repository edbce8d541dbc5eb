// The structural pair list misses no pair that can touch (issue #27, item 2): a small scene of two
// cylindrical bearings side by side on one axis (1 mm apart), posed so that parts that never meet
// at rest do meet — the second bearing's outer ring pushed into the first's, the first's cage
// displaced radially onto its inner raceway and bore, its inner ring displaced into the cage — and an
// independent brute force over ALL part pairs of the scene: the mesh engine (query/clash.h, exact
// predicates on the parts' own meshes) decides which pairs touch; each touching pair must be
// covered by a row of the pair list (its own row, the cage-ring row of its bearing, or the
// bearing-bearing row of its two bearings) whose verdict is not `clear`.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "interfere/bearing/assembly.h"
#include "interfere/query/clash.h"
#include "unit/bearing/assembly_fixture.h"

namespace interfere::bearing {
namespace {

std::string second_bearing() {
  std::string b = test::kCylindricalBearing;
  const auto swap = [&](const std::string& from, const std::string& to) { b.replace(b.find(from), from.size(), to); };
  swap("\"id\": \"cyl\"", "\"id\": \"cyl2\"");
  swap("\"position\": [0, 0, 0]", "\"position\": [0, 0, 31]");
  return b;
}

Transform shifted(const Transform& t, const Vec3& d) {
  Transform out = t;
  out.t = t.t + d;
  return out;
}

TEST(BearingAssemblyStructural, NoTouchingPairIsMissing) {
  Expected<AssemblySpec> s =
      parse_assembly(test::assembly_json("", std::string(test::kCylindricalBearing) + "," + second_bearing()), "two.json");
  ASSERT_TRUE(s) << s.error().message();
  Expected<Assembly> a = build_assembly(*s);
  ASSERT_TRUE(a) << a.error().message();
  const Assembly& as = *a;
  const auto id = [&](const std::string& name) { return static_cast<std::size_t>(as.find(name)); };
  std::vector<Transform> rest;
  for (const AssemblyPart& p : as.parts) rest.push_back(p.rest);
  std::vector<std::vector<Transform>> frames(4, rest);
  frames[1][id("cyl2/outer")] = shifted(rest[id("cyl2/outer")], {0, 0, -2});  // outer rings overlap
  frames[2][id("cyl/cage")] = shifted(rest[id("cyl/cage")], {8, 0, 0});  // webs reach the inner raceway (-x) and the bore (+x)
  frames[3][id("cyl/inner")] = shifted(rest[id("cyl/inner")], {0, 8, 0});  // the inner ring reaches the webs
  // which rows cover a part pair
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> cover;
  const auto key = [](std::size_t p, std::size_t q) { return std::pair{std::min(p, q), std::max(p, q)}; };
  for (std::size_t k = 0; k < as.pairs.size(); ++k) {
    const AssemblyPair& pr = as.pairs[k];
    if (pr.kind == AssemblyPairKind::bearing_bearing) {
      const int bi = as.parts[pr.a].bearing, bj = as.parts[pr.b].bearing;
      for (std::size_t p = 0; p < as.parts.size(); ++p)
        for (std::size_t q = 0; q < as.parts.size(); ++q)
          if (as.parts[p].bearing == bi && as.parts[q].bearing == bj) cover[key(p, q)].push_back(k);
    } else {
      cover[key(pr.a, pr.b)].push_back(k);
    }
  }
  int touching = 0, by_new_kinds = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    std::vector<Model> models;
    for (std::size_t p = 0; p < as.parts.size(); ++p) models.push_back(make_model(transformed(*as.parts[p].mesh, frames[f][p])));
    std::vector<AssemblyPairResult> rows;
    for (const AssemblyPair& pr : as.pairs) rows.push_back(solve_pair(as, pr, frames[f], as.spec.clearance));
    for (std::size_t p = 0; p < as.parts.size(); ++p)
      for (std::size_t q = p + 1; q < as.parts.size(); ++q) {
        ClashRequest rq;
        rq.parallel = false, rq.regions = false;
        const Verdict v = clash(models[p], models[q], rq).verdict;
        if (v != Verdict::clash && v != Verdict::contact) continue;
        ++touching;
        SCOPED_TRACE("frame " + std::to_string(f) + ": " + as.parts[p].id + " - " + as.parts[q].id);
        const auto it = cover.find(key(p, q));
        ASSERT_NE(it, cover.end()) << "a touching pair is missing from the pair list";
        bool flagged = false, structural = false;
        for (std::size_t k : it->second) {
          flagged = flagged || rows[k].verdict != Verdict::clear;
          const AssemblyPairKind kind = as.pairs[k].kind;
          structural = structural || kind == AssemblyPairKind::cage_inner || kind == AssemblyPairKind::cage_outer ||
                       kind == AssemblyPairKind::bearing_bearing;
        }
        EXPECT_TRUE(flagged) << "every row covering a touching pair says clear";
        by_new_kinds += structural;
      }
    if (f == 0)  // at rest the new rows are clear (the bearings and the cage-ring gaps are apart)
      for (std::size_t k = 0; k < as.pairs.size(); ++k)
        if (as.pairs[k].kind == AssemblyPairKind::cage_inner || as.pairs[k].kind == AssemblyPairKind::cage_outer ||
            as.pairs[k].kind == AssemblyPairKind::bearing_bearing)
          EXPECT_EQ(rows[k].verdict, Verdict::clear) << as.parts[as.pairs[k].a].id << " " << as.parts[as.pairs[k].b].id;
  }
  std::printf("[ structural ] %d touching part pairs over 4 frames, %d covered by cage-ring or bearing-bearing rows\n",
              touching, by_new_kinds);
  EXPECT_GE(by_new_kinds, 4);  // outer rings; cage on the inner and outer rings; inner ring on the cage
}

}  // namespace
}  // namespace interfere::bearing
