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

}  // namespace interfere::scene::detail
