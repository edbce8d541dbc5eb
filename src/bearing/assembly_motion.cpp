// Motion of a bearing assembly (assembly.h): the paper's motion generated with a seed (Jia & Zheng
// 2019, §2.3 and §4: rotation about the axes, random perturbations of the tilt, load pressing the
// parts together), or per-frame poses read from a motion file (scene/io.h's reader).
//
// Generated, per bearing and frame f (outer ring fixed):
//   inner ring: rotation omega_i f about the axis, displaced radially by the load (direction, size);
//   cage: rotation omega_c f, omega_c = omega_i (1 - (D / d_m) cos(alpha)) / 2 (the epicyclic cage
//     speed with a fixed outer ring; D the mean roller diameter, d_m = 2 x pitch radius);
//   roller k: orbits with the cage (angle 2 pi k / Z + omega_c f plus a tangential play of up to
//     pocket_play x pocket clearance), spins about its own axis at omega_r = -(d_m / D)
//     (omega_i / 2) (1 - (D cos(alpha) / d_m)^2) relative to the cage, tilts in its axial plane
//     (about the tangential direction through its mid point) by a uniform random angle in
//     [-max_tilt, max_tilt] (Eq. (1)'s validity range is checked by validate_assembly), and shifts
//     axially by up to axial_play x the free play between the ribs.
// The random numbers of (bearing, roller, frame) come from SplitMix64 seeded by a hash of (seed,
// bearing, roller, frame): any frame is reproducible on its own, independent of threads.
#include <cmath>
#include <numbers>

#include "assembly_internal.h"
#include "interfere/bearing/assembly.h"
#include "interfere/bearing/assembly_scene.h"
#include "interfere/bearing/window.h"
#include "interfere/scene/io.h"

namespace interfere::bearing {
namespace {

constexpr double kPi = std::numbers::pi;

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  SplitMix64 g{a ^ (b * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)};
  return g.next();
}

}  // namespace

AssemblyMotion generate_motion(const Assembly& as, int frames, std::uint64_t seed) {
  using detail::compose;
  AssemblyMotion m;
  m.source = "generated (seed " + std::to_string(seed) + ")";
  const AssemblyMotionSpec& ms = as.spec.motion;
  const double deg = kPi / 180;
  m.poses.assign(static_cast<std::size_t>(frames), std::vector<Transform>(as.parts.size()));
  for (int f = 0; f < frames; ++f) {
    std::vector<Transform>& poses = m.poses[static_cast<std::size_t>(f)];
    for (std::size_t i = 0; i < as.parts.size(); ++i) {
      const AssemblyPart& p = as.parts[i];
      const BearingSpec& b = as.spec.bearings[p.bearing];
      const BearingGeometry& g = as.geometry[p.bearing];
      const double omega_i = ms.inner_deg_per_frame * deg;
      const double d_mean = b.type == BearingType::tapered ? b.rollers.radius + b.rollers.top_radius : 2 * b.rollers.radius;
      const double dm = 2 * g.pitch_radius;
      const double cos_a = b.type == BearingType::tapered ? std::cos(g.roller_lean) : 1.0;
      const double omega_c = 0.5 * omega_i * (1 - d_mean / dm * cos_a);
      const double omega_r = -(dm / d_mean) * 0.5 * omega_i * (1 - (d_mean * cos_a / dm) * (d_mean * cos_a / dm));
      switch (p.kind) {
        case PartKind::outer: poses[i] = g.frame; break;
        case PartKind::cage: poses[i] = compose(g.frame, detail::rotation_z(omega_c * f)); break;
        case PartKind::inner: {
          const double a = ms.load_direction_deg * deg;
          const Vec3 shift = Vec3{std::cos(a), std::sin(a), 0} * ms.load_displacement;
          poses[i] = compose(g.frame, compose(detail::translation(shift), detail::rotation_z(omega_i * f)));
          break;
        }
        case PartKind::roller: {
          SplitMix64 rng{mix(mix(mix(seed, static_cast<std::uint64_t>(p.bearing)), static_cast<std::uint64_t>(p.index)),
                             static_cast<std::uint64_t>(f))};
          const double tilt = ms.max_tilt_deg * deg * rng.symmetric();
          const double play = ms.pocket_play * b.cage.pocket_clearance / g.pitch_radius * rng.symmetric();
          const double axial = ms.axial_play * std::max(0.0, g.free_axial_play) * rng.symmetric();
          const double phase = 2 * kPi * rng.uniform();
          const double phi = 2 * kPi * p.index / b.rollers.count + omega_c * f + play;
          poses[i] = compose(g.frame, roller_local_pose(b, g, phi, tilt, axial, phase + omega_r * f));
          break;
        }
      }
    }
  }
  return m;
}

Expected<AssemblyMotion> read_assembly_motion(const Assembly& as, const std::string& path) {
  scene::Scene sc = assembly_scene(as);
  if (Status st = scene::read_motion(path, sc); !st) return st.error();
  AssemblyMotion m;
  m.source = path;
  std::vector<Transform> current;
  for (const AssemblyPart& p : as.parts) current.push_back(p.rest);
  for (const scene::Frame& f : sc.frames) {
    for (const scene::Frame::Pose& pose : f.poses) {
      if (!pose.pose.is_rigid())
        return Error{.file = path,
                     .reason = f.label + ", body '" + as.parts[pose.body].id +
                               "': the pose is not a rotation (a bearing part is rigid): " + pose.pose.non_rigid_note()};
      current[pose.body] = pose.pose;
      // a roller's tilt from its nominal direction (the lean in its axial plane) must lie in Eq. (1)'s
      // validity range (window.h), as the description's max_tilt_deg must
      const AssemblyPart& part = as.parts[pose.body];
      if (part.kind != PartKind::roller) continue;
      const BearingSpec& b = as.spec.bearings[part.bearing];
      const BearingGeometry& g = as.geometry[part.bearing];
      const Vec3 axis = g.frame.rotate({0, 0, 1}), u = pose.pose.rotate({0, 0, 1});
      const Vec3 mid = pose.pose.apply({0, 0, 0.5 * b.rollers.length}) - g.frame.t;
      const Vec3 radial = mid - axis * dot(mid, axis);
      const double rn = norm(radial);
      const Vec3 nominal = rn > 0 ? axis * std::cos(g.roller_lean) + radial * (std::sin(g.roller_lean) / rn) : axis;
      const double tilt = std::atan2(norm(cross(u, nominal)), dot(u, nominal));
      WindowParams wp;
      wp.roller_radius = b.rollers.radius;
      wp.partner_radius = b.type == BearingType::cylindrical ? b.inner_raceway : g.raceway.radius;
      wp.height = b.rollers.length;
      if (!(tilt < max_valid_tilt(wp)))
        return Error{.file = path,
                     .reason = f.label + ", body '" + part.id + "': the roller is tilted by " +
                               short_number(tilt * 180 / kPi) + " degrees from its nominal axis, outside Eq. (1)'s validity range (below " +
                               short_number(max_valid_tilt(wp) * 180 / kPi) + " degrees)"};
    }
    m.poses.push_back(current);
  }
  return m;
}

}  // namespace interfere::bearing
