// The frames x body pairs table and the reference configuration's verdicts (issue #26, items 2 and
// 4): Deng et al. 2018 check every pair of deformed parts at every load step; the user asks which
// pairs clash, from which step, and whether a contact is designed (a bonded or tied interface,
// touching already before the load) or made by the load.
#include <algorithm>
#include <map>
#include <tuple>

#include "engine_internal.h"

namespace interfere::scene::detail {

void summarise_frames(const Scene& scene, const std::vector<ClashTest>& tests, SceneClashResult& result) {
  const auto pair_key = [&](std::uint32_t test, std::uint32_t a, std::uint32_t b) {
    return std::tuple<std::uint32_t, const std::string&, const std::string&>(test, scene.bodies[a].id, scene.bodies[b].id);
  };
  std::sort(result.frame_pairs.begin(), result.frame_pairs.end(), [&](const FramePairRow& x, const FramePairRow& y) {
    if (x.frame != y.frame) return x.frame < y.frame;
    return pair_key(x.test, x.a, x.b) < pair_key(y.test, y.a, y.b);
  });
  std::sort(result.depth_maps.begin(), result.depth_maps.end(), [&](const PairDepthMap& x, const PairDepthMap& y) {
    if (x.frame != y.frame) return x.frame < y.frame;
    return pair_key(0, x.a, x.b) < pair_key(0, y.a, y.b);
  });
  std::sort(result.reference_pairs.begin(), result.reference_pairs.end(), [&](const ReferencePair& x, const ReferencePair& y) {
    return pair_key(x.test, x.a, x.b) < pair_key(y.test, y.a, y.b);
  });
  using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>;  // test, a, b
  std::map<Key, Verdict> reference;
  for (const ReferencePair& r : result.reference_pairs) reference[{r.test, r.a, r.b}] = r.verdict;
  std::map<Key, std::pair<std::int64_t, std::int64_t>> first;  // first frame, first clashing frame
  for (const FramePairRow& r : result.frame_pairs) {
    auto it = first.try_emplace({r.test, r.a, r.b}, r.frame, -1).first;
    if (r.verdict == Verdict::clash && it->second.second < 0) it->second.second = r.frame;
  }
  std::map<std::string, std::uint32_t> test_index;
  for (std::uint32_t k = 0; k < tests.size(); ++k) test_index.emplace(tests[k].name, k);
  const auto key_of = [&](const std::string& test, std::uint32_t a, std::uint32_t b) {
    return Key{test_index.at(test), a, b};
  };
  const auto reference_of = [&](const Key& k) {
    const auto it = reference.find(k);
    return it == reference.end() ? Verdict::clear : it->second;
  };
  for (PairSummary& p : result.pairs) {
    const Key k = key_of(p.test, p.a, p.b);
    if (const auto it = first.find(k); it != first.end())
      p.first_frame = it->second.first, p.first_clash_frame = it->second.second;
    p.reference_verdict = reference_of(k);
  }
  if (!result.reference_checked) return;
  for (SceneClash& c : result.clashes) {
    const Verdict ref = reference_of(key_of(c.test, c.a, c.b));
    if (c.verdict == Verdict::contact) {
      // The pair met before the load: a bonded or tied interface, or a designed fit.
      c.designed = ref == Verdict::contact || ref == Verdict::clash;
      ++(c.designed ? result.designed_contact_count : result.new_contact_count);
    } else if (c.verdict == Verdict::clash) {
      result.new_penetration_count += ref != Verdict::clash;
    }
  }
}

namespace {

VertexDepths sparse(const DepthMap& m) {
  VertexDepths out;
  out.undecided = m.undecided;
  for (std::uint32_t v = 0; v < m.side.size(); ++v)
    if (m.side[v] == 1) out.vertices.push_back(v), out.depths.push_back(m.depth[v]);
  return out;
}

// The source id of a triangle at vertex v (the smallest index), -1 when none.
std::int64_t element_at(const Body& body, std::uint32_t v) {
  const auto& tris = body.mesh->triangles;
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    if (tris[t][0] == v || tris[t][1] == v || tris[t][2] == v) return body.source_id(t);
  return -1;
}

}  // namespace

void keep_deeper(bool& has, DeepestPoint& kept, const DeepestPoint& c) {
  if (!has || c.depth > kept.depth ||
      (c.depth == kept.depth && std::tie(c.frame, c.body, c.vertex) < std::tie(kept.frame, kept.body, kept.vertex))) {
    kept = c;
    has = true;
  }
}

PairDepthMap pair_depth_map(const Scene& scene, const std::function<Vec3(std::uint32_t, std::uint32_t)>& point,
                            std::uint32_t frame,
                            std::uint32_t a, std::uint32_t b, const DepthMaps& maps) {
  PairDepthMap m{.frame = frame, .a = a, .b = b, .a_in_b = sparse(maps.a), .b_in_a = sparse(maps.b)};
  const auto consider = [&](std::uint32_t body, const DepthMap& map) {
    if (map.max_vertex == kNoVertex || !(map.max_depth > 0)) return;
    DeepestPoint d{.body = body, .vertex = map.max_vertex, .depth = map.max_depth, .frame = frame};
    const Body& x = scene.bodies[body];
    d.node = x.vertex_id(map.max_vertex);
    d.element = element_at(x, map.max_vertex);
    d.point = point(body, map.max_vertex);
    keep_deeper(m.has_deepest, m.deepest, d);
  };
  consider(a, maps.a);
  consider(b, maps.b);
  return m;
}

}  // namespace interfere::scene::detail
