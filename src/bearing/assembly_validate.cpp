// Validation of a bearing assembly description (assembly.h, validate_assembly): every error names
// the parameter by its JSON path and says what is wrong and by how much. Never a NaN later: every
// number is finite and every derived quantity (pitch radius of a tapered bearing, webs, Eq. (1)'s
// range) is checked here.
#include <cmath>
#include <numbers>
#include <set>

#include "interfere/bearing/analytic.h"
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/window.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;

Error fail(const std::string& path, const std::string& reason) {
  return Error{.reason = path + ": " + reason};
}
std::string num(double v) { return short_number(v); }

/// The enclosing cylinder of a bearing at rest (world), for the "bearings overlap" check.
Cylinder envelope(const BearingSpec& b, const BearingGeometry& g) {
  Cylinder c;
  c.axis = b.axis;
  if (b.type == BearingType::cylindrical) {
    const double w = std::max(b.inner_width, b.outer_width);
    c.radius = b.outer_radius, c.height = w;
    c.base = b.position - b.axis * (0.5 * w);
  } else {
    c.radius = b.cup_outer, c.height = g.ring_hi - g.ring_lo;
    c.base = b.position + b.axis * g.ring_lo;
  }
  return c;
}

Status validate_cylindrical(const BearingSpec& b) {
  const std::string& w = b.where;
  const RollerSetSpec& r = b.rollers;
  if (!(b.inner_bore > 0)) return fail(w + ".inner_ring.bore_radius", "must be > 0, got " + num(b.inner_bore));
  if (!(b.inner_raceway > b.inner_bore))
    return fail(w + ".inner_ring.raceway_radius",
                "must exceed the bore radius " + num(b.inner_bore) + ", got " + num(b.inner_raceway));
  if (!(b.inner_width > 0)) return fail(w + ".inner_ring.width", "must be > 0, got " + num(b.inner_width));
  if (!(b.rib_height > 0)) return fail(w + ".inner_ring.rib.height", "must be > 0, got " + num(b.rib_height));
  if (!(b.rib_height < r.radius))
    return fail(w + ".inner_ring.rib.height", "must be below the roller radius " + num(r.radius) +
                                                  " (the rib guides the roller's end face), got " + num(b.rib_height));
  if (!(b.rib_width > 0)) return fail(w + ".inner_ring.rib.width", "must be > 0, got " + num(b.rib_width));
  if (!(b.outer_raceway > 0)) return fail(w + ".outer_ring.raceway_radius", "must be > 0, got " + num(b.outer_raceway));
  if (!(b.outer_radius > b.outer_raceway))
    return fail(w + ".outer_ring.outer_radius",
                "must exceed the raceway radius " + num(b.outer_raceway) + ", got " + num(b.outer_radius));
  if (!(b.outer_width >= r.length))
    return fail(w + ".outer_ring.width", "must be at least the roller length " + num(r.length) + ", got " +
                                             num(b.outer_width));
  if (!(r.pitch_radius > 0)) return fail(w + ".rollers.pitch_radius", "must be > 0, got " + num(r.pitch_radius));
  if (r.pitch_radius - r.radius < b.inner_raceway)
    return fail(w + ".rollers.pitch_radius",
                "the rollers do not fit between their rings: pitch radius - roller radius = " +
                    num(r.pitch_radius - r.radius) + " is below the inner raceway radius " + num(b.inner_raceway));
  if (r.pitch_radius + r.radius > b.outer_raceway)
    return fail(w + ".rollers.pitch_radius",
                "the rollers do not fit between their rings: pitch radius + roller radius = " +
                    num(r.pitch_radius + r.radius) + " exceeds the outer raceway radius " + num(b.outer_raceway));
  if (r.length + 2 * b.rib_width > b.inner_width)
    return fail(w + ".rollers.length", "the rollers do not fit between the ribs: length " + num(r.length) +
                                           " + 2 x rib width " + num(b.rib_width) + " exceeds the inner ring width " +
                                           num(b.inner_width));
  return {};
}

Status validate_tapered(const BearingSpec& b, const BearingGeometry& g) {
  const std::string& w = b.where;
  const RollerSetSpec& r = b.rollers;
  if (!(r.top_radius > r.radius))
    return fail(w + ".rollers.top_radius",
                "a tapered roller's large-end radius must exceed its small-end radius " + num(r.radius) + ", got " +
                    num(r.top_radius));
  if (!(b.contact_angle_deg > 0 && b.contact_angle_deg < 60))
    return fail(w + ".contact_angle_deg", "must lie in (0, 60) degrees, got " + num(b.contact_angle_deg));
  const double beta_deg = std::atan((r.top_radius - r.radius) / r.length) * 180 / kPi;
  if (!(b.contact_angle_deg > 2 * beta_deg))
    return fail(w + ".contact_angle_deg",
                "must exceed twice the roller half-angle (" + num(beta_deg) + " degrees) for the cone raceway to exist, got " +
                    num(b.contact_angle_deg));
  if (!(b.cone_bore > 0)) return fail(w + ".cone.bore_radius", "must be > 0, got " + num(b.cone_bore));
  if (!(g.raceway.radius > b.cone_bore))
    return fail(w + ".cone.bore_radius", "must be below the cone raceway's smallest radius " + num(g.raceway.radius) +
                                             ", got " + num(b.cone_bore) + " (the rollers do not fit on the cone)");
  const double cup_hi = (g.ring_hi - g.apex_z) * std::tan(g.cup_half_angle) + b.cup_clearance / std::cos(g.cup_half_angle);
  const double cup_lo = (g.ring_lo - g.apex_z) * std::tan(g.cup_half_angle) + b.cup_clearance / std::cos(g.cup_half_angle);
  if (!(cup_lo > 0)) return fail(w + ".cup.clearance", "makes the cup raceway vanish, got " + num(b.cup_clearance));
  if (!(b.cup_outer > cup_hi))
    return fail(w + ".cup.outer_radius", "must exceed the cup raceway's largest radius " + num(cup_hi) + ", got " +
                                             num(b.cup_outer) + " (the rollers do not fit in the cup)");
  if (b.cone_clearance + b.cup_clearance < 0)
    return fail(w + ".cone.clearance", "cone + cup clearance must be >= 0 (the rollers do not fit between the raceways), got " +
                                           num(b.cone_clearance + b.cup_clearance));
  return {};
}

Status validate_bearing(const AssemblySpec& s, const BearingSpec& b) {
  const std::string& w = b.where;
  if (b.id.empty()) return fail(w + ".id", "must not be empty");
  for (char c : b.id)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':'))
      return fail(w + ".id", "'" + b.id + "': only letters, digits and _ - . : are allowed");
  const RollerSetSpec& r = b.rollers;
  if (r.count < 3 || r.count > 1000) return fail(w + ".rollers.count", "must lie in [3, 1000], got " + std::to_string(r.count));
  if (!(r.radius > 0)) return fail(w + ".rollers.radius", "must be > 0, got " + num(r.radius));
  if (!(r.length > 0)) return fail(w + ".rollers.length", "must be > 0, got " + num(r.length));
  RollerParams rp;
  rp.radius = r.radius, rp.top_radius = r.top_radius, rp.height = r.length;
  rp.radial_segments = r.radial_segments, rp.height_segments = r.height_segments;
  if (Status st = validate(rp, w + ".rollers"); !st) return st;
  if (Status st = b.type == BearingType::cylindrical ? validate_cylindrical(b) : Status{}; !st) return st;
  if (b.type == BearingType::tapered) {
    if (!(r.top_radius > r.radius)) return validate_tapered(b, BearingGeometry{});
    if (!(b.contact_angle_deg > 0 && b.contact_angle_deg < 60)) return validate_tapered(b, BearingGeometry{});
  }
  const double r_min = r.radius, r_max = b.type == BearingType::tapered ? r.top_radius : r.radius;
  // the cage
  const CageSpec& c = b.cage;
  if (c.pocket_clearance < 0)
    return fail(w + ".cage.pocket_clearance", "the cage pocket (width " + num(2 * (r_max + c.pocket_clearance)) +
                                                  ") is smaller than its roller (diameter " + num(2 * r_max) + ")");
  if (!(c.web_thickness > 0 && c.web_thickness < 2 * r_min))
    return fail(w + ".cage.web_thickness", "must lie in (0, " + num(2 * r_min) +
                                               ") (the webs stay between the raceways), got " + num(c.web_thickness));
  if (c.width < 0) return fail(w + ".cage.width", "must be >= 0 (0: the roller length), got " + num(c.width));
  if (b.type == BearingType::cylindrical && c.width > b.inner_width - 2 * b.rib_width)
    return fail(w + ".cage.width", "must fit between the ribs (" + num(b.inner_width - 2 * b.rib_width) + "), got " +
                                       num(c.width));
  Expected<BearingGeometry> g = bearing_geometry(b);
  if (!g) return g.error();
  if (b.type == BearingType::tapered)
    if (Status st = validate_tapered(b, *g); !st) return st;
  // neighbours on the pitch circle (tapered: at both end centres, where the roller radius is r and R)
  const double chord = 2 * std::sin(kPi / r.count);
  if (b.type == BearingType::cylindrical) {
    if (g->pitch_radius * chord < 2 * r.radius)
      return fail(w + ".rollers.count", std::to_string(r.count) + " rollers of radius " + num(r.radius) +
                                            " overlap their neighbours on the pitch circle of radius " +
                                            num(g->pitch_radius) + " (centre distance " + num(g->pitch_radius * chord) + ")");
  } else {
    const double beta = std::atan((r.top_radius - r.radius) / r.length);
    const double d1 = r.radius / std::tan(beta);
    const double rs = d1 * std::sin(g->roller_lean), rl = (d1 + r.length) * std::sin(g->roller_lean);
    if (rs * chord < 2 * r.radius || rl * chord < 2 * r.top_radius)
      return fail(w + ".rollers.count", std::to_string(r.count) + " tapered rollers overlap their neighbours (pitch radius " +
                                            num(g->pitch_radius) + ")");
  }
  // every web must keep a positive width (pockets of width 2 (r + c) leave room for it)
  const double psi = kPi / r.count;
  const Vec3 along{-std::sin(psi), std::cos(psi), 0};  // tangential at web 0
  const CageWeb& web = g->webs[0];
  for (int i = 0; i < 8; i += 2) {
    const double width = dot(web.corners[i + 1] - web.corners[i], along);
    if (!(width > 0))
      return fail(w + ".cage.pocket_clearance",
                  "pockets of width " + num(2 * (r_max + c.pocket_clearance)) + " leave no web between neighbouring rollers " +
                      "(web width " + num(width) + " at a corner); fewer rollers, a smaller clearance or a thinner web");
  }
  // Eq. (1)'s validity range (window.h): roller against the inner raceway
  WindowParams wp;
  wp.roller_radius = r_min;
  wp.partner_radius = b.type == BearingType::cylindrical ? b.inner_raceway : g->raceway.radius;
  wp.height = r.length;
  wp.max_tilt = s.motion.max_tilt_deg * kPi / 180;
  if (Status st = validate(wp); !st)
    return fail("motion.max_tilt_deg", "outside Eq. (1)'s validity range for " + w + " (" + st.error().reason +
                                           "; at most " + num(max_valid_tilt(wp) * 180 / kPi) + " degrees)");
  return {};
}

}  // namespace

Status validate_assembly(const AssemblySpec& s) {
  if (s.frames < 1 || s.frames > 10'000'000) return fail("frames", "must lie in [1, 10^7], got " + std::to_string(s.frames));
  if (!(s.clearance >= 0) || !std::isfinite(s.clearance)) return fail("clearance", "must be >= 0, got " + num(s.clearance));
  if (s.ring_segments < 8 || s.ring_segments > 4096)
    return fail("ring_segments", "must lie in [8, 4096], got " + std::to_string(s.ring_segments));
  const AssemblyMotionSpec& m = s.motion;
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(m.inner_deg_per_frame)) return fail("motion.inner_deg_per_frame", "must be finite");
  if (!(m.max_tilt_deg >= 0) || !finite(m.max_tilt_deg))
    return fail("motion.max_tilt_deg", "must be >= 0, got " + num(m.max_tilt_deg));
  if (!finite(m.load_direction_deg)) return fail("motion.load.direction_deg", "must be finite");
  if (!(m.load_displacement >= 0) || !finite(m.load_displacement))
    return fail("motion.load.displacement", "must be >= 0, got " + num(m.load_displacement));
  if (!(m.pocket_play >= 0 && m.pocket_play <= 4)) return fail("motion.pocket_play", "must lie in [0, 4], got " + num(m.pocket_play));
  if (!(m.axial_play >= 0 && m.axial_play <= 4)) return fail("motion.axial_play", "must lie in [0, 4], got " + num(m.axial_play));
  if (!(s.scar_fraction >= 0 && s.scar_fraction <= 1)) return fail("scar.fraction", "must lie in [0, 1], got " + num(s.scar_fraction));
  const RollerScarImport& im = s.scar_import;  // an imported roller scar (issue #27)
  if (im.any()) {
    const std::string key = !im.map.empty() ? "scar.map" : !im.png.empty() ? "scar.png" : "scar.points";
    if (!(s.scar_fraction > 0)) return fail("scar.fraction", "must be > 0 with " + key + " (the rollers that carry it)");
    if (im.border < 0) return fail("scar.border", "must be >= 0, got " + std::to_string(im.border));
    if (!im.png.empty() && !(im.png_scale != 0)) return fail("scar.scale", "must be non-zero (mm per pixel unit)");
    if (!(im.points_window >= 0)) return fail("scar.window", "must be >= 0 (0 = automatic), got " + num(im.points_window));
  }
  std::set<std::string> ids;
  for (const BearingSpec& b : s.bearings) {
    if (!ids.insert(b.id).second) return fail(b.where + ".id", "'" + b.id + "' is used by another bearing");
    if (Status st = validate_bearing(s, b); !st) return st;
    if (m.load_displacement >= b.rollers.radius)
      return fail("motion.load.displacement", "must be below the roller radius " + num(b.rollers.radius) + " of " +
                                                  b.where + ", got " + num(m.load_displacement));
    if (s.scar_fraction > 0 && !im.any()) {  // (an import: its reader and resampling check it)
      ScarParams sc = s.scar;
      if (sc.z_min < 0) sc.z_min = 0.25 * b.rollers.length;
      if (sc.z_max < 0) sc.z_max = 0.75 * b.rollers.length;
      RollerParams rp;
      rp.radius = b.rollers.radius, rp.height = b.rollers.length;
      if (b.type == BearingType::tapered) rp.top_radius = b.rollers.top_radius;  // depth below the small end's radius
      rp.radial_segments = b.rollers.radial_segments, rp.height_segments = b.rollers.height_segments;
      if (Status st = validate(sc, rp, "scar"); !st) return fail(b.where, st.error().reason);
    }
  }
  // bearings apart at rest (the bearing-bearing rows catch a motion that brings them together): their enclosing cylinders are disjoint
  for (std::size_t i = 0; i < s.bearings.size(); ++i)
    for (std::size_t j = i + 1; j < s.bearings.size(); ++j) {
      const Expected<BearingGeometry> gi = bearing_geometry(s.bearings[i]), gj = bearing_geometry(s.bearings[j]);
      const PairDistance d = cylinder_pair_distance(envelope(s.bearings[i], *gi), envelope(s.bearings[j], *gj));
      if (!(d.distance > 0))
        return fail(s.bearings[j].where + ".position",
                    "bearing '" + s.bearings[j].id + "' overlaps bearing '" + s.bearings[i].id +
                        "' (their enclosing cylinders meet; bearings of one assembly must lie apart)");
    }
  return {};
}

}  // namespace interfere::bearing
