// The paper's inspection machine exactly (Li, Zhou & Zheng 2008, §3.1; issue #28, deliverables 1-2):
// three prismatic joints A1-A3 = x, y, z and two revolute joints A4 = a, A5 = b. §3.1 gives the
// centre of the probe's REAR end circle as
//
//   R = (x + d1 cos a + d2 sin a cos b,  y - d1 sin a + d2 cos a cos b,  -z + d2 sin b)
//
// with d1 the structural constant and d2 the clamping length. Read geometrically: the wrist point
// is (x, y, -z) (the z slide moves down), d1 runs along e = (cos a, -sin a, 0) (the A5 axis) and d2
// along u = (sin a cos b, cos a cos b, sin b), the probe axis: horizontal (world +y) at a = b = 0,
// turned by -a about the vertical and tilted up by b. The probe points along u, so its front end
// circle (ProbePose::tip) is R + l u for a probe of length l, and ProbePose::axis = u.
//
// As a standard DH chain (kinematics.h, T_i = Rz(theta) Tz(d) Tx(a) Rx(alpha)), base rotation
// frame 0 = (x0, y0, z0) = (world y, world z, world x), translation `origin`:
//
//   joint  type       theta  d    a    alpha
//   x      prismatic   90    0    0    90      z1 = world y
//   y      prismatic  -90    0    0    90      z2 = world -z
//   z      prismatic    0    0    0     0      z3 = world -z
//   a      revolute   -90    0    0    90      z4 = e
//   b      revolute   180    d1   d2    0      x5 = u, origin of frame 5 = R
//   tool: tip (l, 0, 0), axis (1, 0, 0)
//
// (data/examples/probe_paper_machine.json with d1 = 30, d2 = 120, l = 40; docs/probe.md.)
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/probe/kinematics.h"
#include "interfere/probe/path.h"

namespace interfere::probe {

struct PaperMachine {
  double d1 = 30;            ///< structural constant (offset along the A5 axis), mm
  double d2 = 120;           ///< clamping length (wrist to the probe's rear end circle), mm
  double probe_length = 40;  ///< rear to front end circle, mm (the tool tip is at d2 + probe_length)
  Vec3 origin{};             ///< world position of the wrist point at x = y = z = 0
  double travel = 2000;      ///< x, y, z in [-travel, travel]
  double a_limit = 360;      ///< a in [-a_limit, a_limit] degrees
  double b_limit = 120;      ///< b in [-b_limit, b_limit] degrees
};

/// The §3.1 machine as a DH chain (table above), named "paper-3P2R".
Robot paper_machine_31(const PaperMachine& m = {});

/// The geometry that inverse kinematics needs, when `robot` has the DH structure above (any d1,
/// d2, tool offset, base translation and limits): d1, the reach from the wrist to the front tip
/// along u (d2 + tool tip x) and the origin. nullopt for any other chain.
struct PaperGeometry {
  double d1 = 0;
  double reach = 0;
  Vec3 origin{};
};
std::optional<PaperGeometry> paper_geometry(const Robot& robot);
inline bool has_inverse_kinematics(const Robot& robot) { return paper_geometry(robot).has_value(); }

/// Analytic inverse kinematics of the §3.1 machine: joint values (x, y, z, a, b) putting the front
/// end circle at pose.tip with direction pose.axis. Of the solutions (b = atan2(u_z, |u_xy|) with
/// a = atan2(u_x, u_y), or b' = 180 - b with a' = a + 180, each angle shifted by multiples of 360)
/// those within every joint limit are kept and the one nearest to `previous` (when given; else to
/// a = b = 0) is returned; when the axis is vertical a is free and `previous`'s a (or 0) is used.
/// Errors: the robot has no inverse kinematics, or no solution is within the limits (the reason
/// names the violated joint, its value and its limits).
Expected<std::vector<double>> inverse_kinematics(const Robot& robot, const ProbePose& pose,
                                                 const std::vector<double>* previous = nullptr);

/// A pose path turned into the robot's joint path (issue #28, deliverable 2), so the motion
/// between points is the machine's own (joint interpolation in sweep): joint values by
/// inverse_kinematics, each nearest to the previous point's; poses re-derived by forward
/// kinematics. Errors name the file, the line and the point: "path.csv:7: point 5 (tip ..., axis
/// ...): not reachable by robot 'paper-3P2R': joint z = 2100 outside its limits [-2000, 2000]".
/// A joint path is returned unchanged.
Expected<ProbePath> pose_path_to_joint_path(const ProbePath& path, const Robot& robot, const std::string& file_name);

}  // namespace interfere::probe
