// A STEP assembly as a scene (issue #24, item 1): one body per instance of the product tree, with
// the product's name and path, its part's tessellation (shared by the instances of one part) tagged
// with B-Rep face ids, and the nominal-fit check of assembly-clash (assembly_fit.cpp) as the scene
// engine's hook (scene/engine.h, SceneClashOptions::nominal_fit).
#pragma once
#include <cstdint>
#include <functional>

#include "interfere/cad/model.h"
#include "interfere/query/clash.h"
#include "interfere/query/model.h"
#include "interfere/scene/engine.h"
#include "interfere/scene/scene.h"

namespace interfere::cad {

/// One body per instance, body i = model.instances[i]: id from the instance's product path
/// (scene::make_body_id, made unique), name the instance's (its own, else its product's), path the
/// product path ("/ASM/SUB/PLATE"), source {step_instance, CadModel::file, the instance's path},
/// unit and scene unit model.units (mm), mesh the part's tessellation welded exactly (one shared
/// mesh per part), pose the instance's placement, source ids the B-Rep face of each triangle
/// (brep_face, 1-based: TopExp::MapShapes order), tessellation_error the part's
/// (Part::tessellation_error). The scene's warnings are the model's.
scene::Scene assembly_scene(const CadModel& model);

/// The nominal-fit check (assembly_clash.h, InstancePairResult::nominal_fit) for the scene engine
/// (SceneClashOptions::nominal_fit): the crossings of two bodies of `s` that come from instances
/// of `model` (source step_instance, detail the instance's path, as assembly_scene makes them) lie
/// only where their B-Rep faces coincide, with a depth within the sum of the two parts'
/// tessellation errors. The faces are placed where the body is: its pose in `s` when the world
/// model is that pose's image, else the rigid motion that maps the body's mesh onto its world model
/// (a frame's pose). Bodies not from `model`, parts without an AAG (ImportOptions::build_aag) and
/// non-rigid placements are never a fit (their crossings stay clashes). `model` and `s` must
/// outlive the returned callable.
std::function<bool(std::uint32_t a, std::uint32_t b, const Model& wa, const Model& wb,
                   const ClashResult& r, double depth)>
nominal_fit_check(const CadModel& model, const scene::Scene& s);

/// The zero-clearance fits of assembly-clash (issue #29, item 4) for the scene engine
/// (SceneClashOptions::zero_clearance_fits): two bodies of `s` from instances of `model` (as for
/// nominal_fit_check), rigidly posed, with coincident B-Rep faces back to back (planes; cylinders or
/// spheres of one radius) within kFitTolerance of the two parts' diagonals whose placed triangles come
/// that near, are a contact whatever their tessellations (the AS1 AP203 export's bracket 1.3e-12 mm
/// above its plate). `reach`: kFitTolerance of the body's part diagonal, in the scene's units. A
/// body's placement is its pose (in mm: the scene's units converted). `model` must outlive it.
scene::SceneClashOptions::ZeroClearanceFits zero_clearance_fit_check(const CadModel& model, const scene::Scene& s);

}  // namespace interfere::cad
