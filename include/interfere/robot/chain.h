// Serial robot chains read from URDF (issue #28, deliverable 2): links with their collision
// meshes attached to their frames, joints (revolute, continuous, prismatic, fixed) with origins and
// limits, forward kinematics and joint paths matched by joint name. The DH chains of the probe
// module (probe/kinematics.h) stay as they are; this is the general form a URDF file describes.
//
// Units: lengths in mm (URDF's metres are multiplied by 1000 on reading, mesh scale included),
// joint values in DEGREES for revolute and continuous joints and in mm for prismatic joints, as in
// the probe module's path files (docs/probe.md, "URDF robots").
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/core/transform.h"
#include "interfere/core/vec.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::robot {

enum class JointKind : std::uint8_t { revolute, continuous, prismatic, fixed };
const char* joint_kind_name(JointKind k);

struct ChainJoint {
  std::string name;
  JointKind kind = JointKind::fixed;
  std::string parent, child;  ///< link names
  /// Parent link frame <- joint frame at joint value 0 (URDF <origin xyz rpy>; mm).
  Transform origin;
  Vec3 axis{1, 0, 0};  ///< unit, in the joint frame (URDF <axis>)
  /// Limits in joint units (degrees or mm); continuous joints have none (+-1e300).
  double lower = -1e300, upper = 1e300;
  bool movable() const { return kind != JointKind::fixed; }
};

struct ChainLink {
  std::string name;
  /// The link's collision geometry (URDF <collision> elements, or <visual> when a link has none),
  /// in the link frame, merged into one mesh (mm); null for a link without geometry.
  std::shared_ptr<const TriMesh> mesh;
  std::vector<std::string> mesh_files;  ///< the mesh files it was read from (resolved paths)
};

/// A serial chain: links[0] is the root, joints[i] connects links[i] (parent) to links[i + 1].
struct Chain {
  std::string name;
  std::string file;  ///< where it was read from (errors, reports)
  std::vector<ChainLink> links;
  std::vector<ChainJoint> joints;
  /// Indices into `joints` of the movable joints, in chain order: a joint vector q has one value
  /// per movable joint, in this order.
  std::vector<std::size_t> movable;
  std::size_t dof() const { return movable.size(); }
  /// Index of the link named `name`, or -1.
  std::int64_t find_link(std::string_view name) const;
  /// Index into `movable` of the movable joint named `name`, or -1.
  std::int64_t find_movable(std::string_view name) const;
};

/// The frame of every link (world <- link i), base <- root being `base`, at joint values q
/// (q.size() == chain.dof(); degrees / mm): link i+1 = link i * origin_i * motion_i(q), with
/// motion a rotation by q about the axis (revolute, continuous) or a translation by q along it
/// (prismatic), identity for fixed joints.
std::vector<Transform> link_frames(const Chain& chain, const std::vector<double>& q,
                                   const Transform& base = {});

/// A joint value outside its limits: an error naming the joint, its value and its limits.
Status check_limits(const Chain& chain, const std::vector<double>& q);

/// Where package://NAME/... mesh names are looked for: DIR/NAME/... for each directory in order
/// (then each directory of the ROS_PACKAGE_PATH environment variable, ':'-separated).
struct UrdfOptions {
  std::vector<std::filesystem::path> package_paths;
  bool use_ros_package_path = true;
};

/// Reads a URDF file with urdfdom (Debian liburdfdom-dev): the kinematic tree must be a serial
/// chain (no link with two child joints; urdfdom itself rejects loops, i.e. a link with two
/// parents); joints revolute, continuous, prismatic or fixed (floating and planar joints, an
/// unknown type and revolute/prismatic joints without limits are errors); link geometry meshes
/// (STL, OBJ, PLY, OFF by their extension; relative names are relative to the URDF's directory;
/// file:// and package:// names, see UrdfOptions), boxes, cylinders (32 sides) and spheres
/// (tessellated). Every error names the file and the element (link, joint, mesh file); urdfdom's
/// own parse messages are passed on. A build without urdfdom answers that it has no URDF reader.
Expected<Chain> read_urdf(const std::filesystem::path& file, const UrdfOptions& options = {});
/// The same from URDF text; `file` names it in errors and anchors relative mesh names.
Expected<Chain> parse_urdf(const std::string& text, const std::filesystem::path& file,
                           const UrdfOptions& options = {});
/// Whether this build reads URDF (urdfdom found at configure time).
bool has_urdf_reader();

/// A joint path for a chain: a CSV whose header names the chain's movable joints (any order, each
/// exactly once; matched by name), one row per path point, values in joint units. '#' comment
/// lines and blank lines are skipped. Errors name the file, the line and the column: an unknown or
/// duplicate joint name, a missing joint, a row with the wrong number of values, a value that is
/// not a finite number or lies outside the joint's limits.
struct JointPath {
  std::vector<std::vector<double>> q;  ///< per point, in the chain's movable-joint order
  std::vector<std::int64_t> lines;     ///< the source line of each point
  std::size_t size() const { return q.size(); }
};
Expected<JointPath> parse_joint_csv(std::string_view text, const std::string& file,
                                    const Chain& chain);
Expected<JointPath> read_joint_csv(const std::filesystem::path& file, const Chain& chain);

}  // namespace interfere::robot
