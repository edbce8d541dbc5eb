// Machining-feature recognition on the AAG (issue #6, item 3), after He & Xu (SJTU 2023) §2.2:
// decomposition into minimal AAGs (split at inner loops, then at convex arcs) and matching of
// feature patterns from a JSON library by attributed subgraph isomorphism (node surface type and
// hole/boss sense, arc curve type and convexity, arc counts) plus geometric checks (coaxial
// cylinders, radius order, planes perpendicular to the axis, parallel opposite walls). OCCT-free.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "interfere/cad/model.h"

namespace interfere::cad {

struct PatternNode {
  std::string role;
  std::vector<SurfaceType> types;  ///< any of these
  int hole = -1;                   ///< -1 any, 0 boss sense, 1 hole sense (curved faces)
  int concave_arcs = -1, convex_arcs = -1;  ///< exact counts over the face's arcs, -1 any
  int min_convex_arcs = -1;
};
struct PatternArc {
  std::string a, b;  ///< roles
  std::vector<CurveType> curves;   ///< any of these (empty = any)
  std::vector<Convexity> convexity;
};
struct PatternCheck {
  std::string kind;                ///< coaxial, radius_less, perpendicular_to_axis, parallel_planes, opposite_normals, perpendicular_planes, full_circle, distinct
  std::vector<std::string> roles;
};
struct FeaturePattern {
  std::string type;                ///< e.g. "through_hole"
  int priority = 0;                ///< higher first; faces claimed by a match are not reused
  std::vector<PatternNode> nodes;
  std::vector<PatternArc> arcs;
  std::vector<PatternCheck> checks;
};
struct FeatureLibrary {
  std::vector<FeaturePattern> patterns;
  bool has(const std::string& type) const;
  /// The role names of the type's patterns, in order of first appearance (empty: unknown type).
  std::vector<std::string> roles(const std::string& type) const;
};

/// Parses a library (docs/simplify.md "Feature library"); errors name the pattern and the field.
Expected<FeatureLibrary> parse_feature_library(const std::string& json_text, const std::string& source = "");
Expected<FeatureLibrary> load_feature_library(const std::filesystem::path& path);
/// The library installed with interfere (data/features/library.json); INTERFERE_DATA_DIR or the
/// source tree's copy.
Expected<FeatureLibrary> default_feature_library();

struct Feature {
  std::string type;
  std::map<std::string, std::uint32_t> roles;  ///< role -> face id (the first of its faces)
  /// role -> every face of it (a surface split by the modeller, e.g. two half cylinders joined by
  /// smooth edges on the same axis and radius, is matched as one node)
  std::map<std::string, std::vector<std::uint32_t>> role_faces;
  std::vector<std::uint32_t> faces;            ///< sorted face ids
  Vec3 axis_point, axis;                       ///< rotational features (zero axis otherwise)
  std::vector<double> radii;                   ///< of the cylinders/cones, in role order
};

/// Minimal AAGs (§2.2): connected components after removing the arcs on inner loops, then the
/// convex arcs; each is a sorted list of face ids.
std::vector<std::vector<std::uint32_t>> minimal_subgraphs(const Aag& aag);

/// Graph matching of a minimal AAG against a library pattern's own nodes (its non-shared roles and the
/// arcs between them; He & Xu §2.2, issue #29). Attributes: surface type and hole sense of a node,
/// curve type and convexity of an arc; several arcs between two faces count once (per neighbouring
/// face). No geometric checks.
enum class GraphMatch : std::uint8_t {
  exact,  ///< attributed graph isomorphism: a bijection of the nodes preserving node attributes and every arc
  paper,  ///< the paper's steps 1-5: equal node and arc counts, and every node of either graph has a node of the
          ///< other with equal attributes and equal first-order arcs (weaker: it accepts some non-isomorphic graphs)
};

struct MaagSubgraph {
  std::vector<std::uint32_t> faces;  ///< face ids, sorted
  int stage = 1;                     ///< 1: a subgraph of SG1 (split at inner loops) matched as it is; 2: of SG2
  std::string type;                  ///< the first pattern (by priority) it matches; empty: none
};

/// The paper's two-stage decomposition used for matching (§2.2): (1) split the AAG at the arcs of inner
/// loops into SG1; (2) match each subgraph of SG1 against the library; (3) split the unmatched ones at
/// their convex arcs into SG2 and match those; (4) SG = the matched subgraphs of SG1 and all of SG2.
/// Split faces (smooth arcs on one surface) are merged first, as recognize_features does. Sorted by
/// smallest face.
std::vector<MaagSubgraph> maag_decomposition(const Aag& aag, const FeatureLibrary& library, GraphMatch method,
                                             double tolerance = 1e-6);

/// All features, patterns tried by decreasing priority, each face claimed at most once per role
/// kind ("owned" roles: the feature's own faces; shared base faces such as a hole's top face may
/// be reused). Sorted by (type, smallest face).
std::vector<Feature> recognize_features(const Aag& aag, const FeatureLibrary& library,
                                        double tolerance = 1e-6);

}  // namespace interfere::cad
