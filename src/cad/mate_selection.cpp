// The assembly features picked by the mates inferred from geometry (include/interfere/cad/mates.h,
// select_mate_features; issue #29, item 4): each mate stands for the process step that would mount
// it (He & Xu 2023 §3: the assembly constraint decides which features a step keeps), its constraint
// taken from the hole type (infer_mates), its rule from the semantic rules.
#include <algorithm>
#include <map>
#include <tuple>

#include "interfere/cad/mates.h"

namespace interfere::cad {
namespace {

void add_unique(std::vector<std::uint32_t>& to, const std::vector<std::uint32_t>& from) {
  to.insert(to.end(), from.begin(), from.end());
  std::sort(to.begin(), to.end());
  to.erase(std::unique(to.begin(), to.end()), to.end());
}

}  // namespace

MateSelection select_mate_features(const CadModel& model, const FeatureLibrary& library, const SemanticRules& rules) {
  MateSelection out;
  out.mates = infer_mates(model, library);
  out.parts.resize(model.parts.size());
  out.instances.assign(model.instances.size(), 0);
  std::vector<std::vector<Feature>> features(model.parts.size());
  for (std::size_t i = 0; i < model.parts.size(); ++i) features[i] = recognize_features(model.parts[i].aag, library);
  // One selection per (part, hole, constraint): six bolts in one part's six holes are six, the same
  // hole met by the instances of a part once.
  std::map<std::tuple<std::uint32_t, std::vector<std::uint32_t>, std::string>, bool> done;
  for (const Mate& m : out.mates) {
    out.instances[m.instance_a] = out.instances[m.instance_b] = 1;
    const std::uint32_t pa = model.instances[m.instance_a].part, pb = model.instances[m.instance_b].part;
    Selection& sa = out.parts[pa];
    Selection& sb = out.parts[pb];
    if (m.kind == Mate::Kind::planar_contact) {
      const auto area = [](const Part& p, const std::vector<std::uint32_t>& faces) {
        double a = 0;
        for (std::uint32_t f : faces) a += f < p.aag.nodes.size() ? p.aag.nodes[f].area : 0.0;
        return a;
      };
      const double a = area(model.parts[pa], m.faces_a), b = area(model.parts[pb], m.faces_b);
      if (a <= b) add_unique(sa.faces, m.faces_a);
      if (b <= a) add_unique(sb.faces, m.faces_b);
      continue;
    }
    add_unique(sb.faces, m.faces_b);  // the inserted cylinder
    if (!done.emplace(std::make_tuple(pa, m.faces_a, m.constraint), true).second) continue;
    const auto f = std::find_if(features[pa].begin(), features[pa].end(),
                                [&](const Feature& x) { return x.faces == m.faces_a && x.type == m.feature_type; });
    if (f == features[pa].end()) {  // (infer_mates recognises the same features)
      add_unique(sa.faces, m.faces_a);
      continue;
    }
    const bool known = std::any_of(rules.rules.begin(), rules.rules.end(),
                                   [&](const SemanticRule& r) { return r.constraint == m.constraint; });
    Selection one;
    if (known) {
      const Process step{{ProcessStep{"mates", {"*"}, m.constraint}}};
      auto sel = select_step_features(step, "mates", rules, model.parts[pa].name, {*f}, &model.parts[pa].aag);
      if (sel) one = std::move(*sel);
    }
    for (std::string& w : one.warnings)  // (not the rules that found no hole of their other types)
      if (w.find(" skips ") != std::string::npos) out.warnings.push_back(std::move(w));
    if (one.faces.empty() && one.annuli.empty()) {
      add_unique(sa.faces, f->faces);
      continue;
    }
    add_unique(sa.faces, one.faces);
    sa.annuli.insert(sa.annuli.end(), one.annuli.begin(), one.annuli.end());
  }
  for (Selection& s : out.parts)  // an annulus on a face kept whole anyway adds nothing
    std::erase_if(s.annuli, [&](const Annulus& a) { return std::binary_search(s.faces.begin(), s.faces.end(), a.face); });
  return out;
}

}  // namespace interfere::cad
