// URDF robots through urdfdom (Debian liburdfdom-dev; issue #28, deliverable 2; robot/chain.h).
// urdfdom parses the XML and builds the link/joint tree; this file checks that the tree is a serial
// chain of supported joints, converts it to mm and degrees and reads the link meshes.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <numbers>
#include <sstream>

#include "interfere/mesh/generate.h"
#include "interfere/mesh/io.h"
#include "interfere/probe/cylinder.h"
#include "interfere/probe/export.h"
#include "interfere/robot/chain.h"

#ifdef INTERFERE_WITH_URDF
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>
#endif

namespace interfere::robot {

bool has_urdf_reader() {
#ifdef INTERFERE_WITH_URDF
  return true;
#else
  return false;
#endif
}

Expected<Chain> read_urdf(const std::filesystem::path& file, const UrdfOptions& options) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error{.file = file.string(), .reason = "cannot open the URDF file"};
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_urdf(ss.str(), file, options);
}

#ifndef INTERFERE_WITH_URDF

Expected<Chain> parse_urdf(const std::string&, const std::filesystem::path& file,
                           const UrdfOptions&) {
  return Error{
      .file = file.string(),
      .reason = "this build has no URDF reader (configure with urdfdom, Debian liburdfdom-dev)"};
}

#else

namespace {

constexpr double kMm = 1000.0;  // URDF lengths are metres

/// Collects urdfdom's console_bridge messages of one parse (the handler is process-wide: one parse
/// at a time).
struct Capture : console_bridge::OutputHandler {
  std::vector<std::string> messages;
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
  }
};
std::mutex g_parse_mutex;

std::int64_t line_of(const std::string& text, std::size_t pos) {
  return pos == std::string::npos
             ? -1
             : 1 + std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n');
}

/// The line of <tag ... name="NAME" (best effort; -1 when not found).
std::int64_t element_line(const std::string& text, const std::string& tag,
                          const std::string& name) {
  for (const char q : {'"', '\''}) {
    const std::string key = std::string("name=") + q + name + q;
    for (std::size_t p = text.find(key); p != std::string::npos; p = text.find(key, p + 1)) {
      const std::size_t open = text.rfind('<', p);
      if (open != std::string::npos && text.compare(open + 1, tag.size(), tag) == 0)
        return line_of(text, open);
    }
  }
  return -1;
}

/// The first "[...]" of a urdfdom message (the element it names), or "".
std::string bracketed(const std::string& m) {
  const std::size_t a = m.find('['), b = a == std::string::npos ? a : m.find(']', a);
  return b == std::string::npos ? std::string() : m.substr(a + 1, b - a - 1);
}

Transform to_transform(const urdf::Pose& p) {
  double x = p.rotation.x, y = p.rotation.y, z = p.rotation.z, w = p.rotation.w;
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  x /= n, y /= n, z /= n, w /= n;
  Transform t;
  t.r = {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
  t.t = Vec3{p.position.x, p.position.y, p.position.z} * kMm;
  return t;
}

void append(TriMesh& out, const TriMesh& m, const Transform& t, const Vec3& scale) {
  const auto base = static_cast<std::uint32_t>(out.positions.size());
  for (const Vec3& p : m.positions)
    out.positions.push_back(t.apply(Vec3{p.x * scale.x, p.y * scale.y, p.z * scale.z}));
  for (const Tri& tr : m.triangles)
    out.triangles.push_back({tr[0] + base, tr[1] + base, tr[2] + base});
}

struct Reader {
  const std::string& text;
  std::filesystem::path file;
  const UrdfOptions& options;

  Error fail(std::int64_t line, const std::string& reason) const {
    return Error{.file = file.string(), .line = line, .reason = reason};
  }

  /// Resolves a mesh filename: relative to the URDF, file://, package://NAME/REST.
  Expected<std::filesystem::path> resolve(const std::string& name, const std::string& link) const {
    const std::int64_t line = element_line(text, "link", link);
    const std::string where = "link '" + link + "', mesh '" + name + "': ";
    if (name.rfind("package://", 0) == 0) {
      const std::string rest = name.substr(10);
      std::vector<std::filesystem::path> dirs = options.package_paths;
      if (options.use_ros_package_path) {
        if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
          std::string s = env;
          for (std::size_t a = 0; a <= s.size();) {
            std::size_t b = s.find(':', a);
            if (b == std::string::npos) b = s.size();
            if (b > a) dirs.emplace_back(s.substr(a, b - a));
            a = b + 1;
          }
        }
      }
      std::string tried;
      for (const auto& d : dirs) {
        const std::filesystem::path p = d / rest;
        if (std::filesystem::is_regular_file(p)) return p;
        tried += (tried.empty() ? "" : ", ") + p.string();
      }
      return fail(
          line,
          where + "package:// name not found " +
              (dirs.empty() ? std::string("(no package search path: give package_paths in the cell "
                                          "file or set ROS_PACKAGE_PATH)")
                            : "(tried " + tried + ")"));
    }
    std::filesystem::path p = name.rfind("file://", 0) == 0 ? std::filesystem::path(name.substr(7))
                                                            : std::filesystem::path(name);
    if (p.is_relative()) p = file.parent_path() / p;
    if (!std::filesystem::is_regular_file(p))
      return fail(line, where + "file not found (" + p.string() + ")");
    return p;
  }

  Expected<ChainLink> link(const urdf::Link& l) const {
    ChainLink out;
    out.name = l.name;
    TriMesh merged;
    auto add = [&](const urdf::GeometrySharedPtr& g, const urdf::Pose& origin) -> Status {
      if (!g) return {};
      const Transform t = to_transform(origin);
      switch (g->type) {
        case urdf::Geometry::MESH: {
          const auto& m = static_cast<const urdf::Mesh&>(*g);
          Expected<std::filesystem::path> p = resolve(m.filename, l.name);
          if (!p) return p.error();
          Expected<TriMesh> mesh = read_mesh(*p);
          if (!mesh) {
            Error e = mesh.error();
            e.reason = "link '" + l.name + "' (" + file.string() + "), mesh '" + m.filename +
                       "': " + e.reason;
            return e;
          }
          append(merged, *mesh, t, Vec3{m.scale.x, m.scale.y, m.scale.z} * kMm);
          out.mesh_files.push_back(p->string());
          return {};
        }
        case urdf::Geometry::BOX: {
          const auto& b = static_cast<const urdf::Box&>(*g);
          const Vec3 h = Vec3{b.dim.x, b.dim.y, b.dim.z} * (kMm / 2);
          append(merged, make_box(-1.0 * h, h), t, {1, 1, 1});
          return {};
        }
        case urdf::Geometry::CYLINDER: {
          const auto& c = static_cast<const urdf::Cylinder&>(*g);
          const double h = c.length * kMm / 2;
          append(merged, probe::cylinder_mesh({{0, 0, -h}, {0, 0, h}, c.radius * kMm}, 32), t,
                 {1, 1, 1});
          return {};
        }
        case urdf::Geometry::SPHERE: {
          const auto& s = static_cast<const urdf::Sphere&>(*g);
          append(merged, make_sphere({.target_triangles = 512, .radius = s.radius * kMm}), t,
                 {1, 1, 1});
          return {};
        }
      }
      return fail(element_line(text, "link", l.name),
                  "link '" + l.name + "': unknown geometry type");
    };
    if (!l.collision_array.empty()) {
      for (const auto& c : l.collision_array) {
        if (Status s = add(c->geometry, c->origin); !s) return s.error();
      }
    } else {
      for (const auto& v : l.visual_array) {
        if (Status s = add(v->geometry, v->origin); !s) return s.error();
      }
    }
    if (!merged.triangles.empty()) out.mesh = std::make_shared<TriMesh>(std::move(merged));
    return out;
  }

  Expected<ChainJoint> joint(const urdf::Joint& j) const {
    ChainJoint out;
    out.name = j.name;
    out.parent = j.parent_link_name;
    out.child = j.child_link_name;
    out.origin = to_transform(j.parent_to_joint_origin_transform);
    const std::int64_t line = element_line(text, "joint", j.name);
    const std::string where = "joint '" + j.name + "': ";
    switch (j.type) {
      case urdf::Joint::REVOLUTE:
        out.kind = JointKind::revolute;
        break;
      case urdf::Joint::CONTINUOUS:
        out.kind = JointKind::continuous;
        break;
      case urdf::Joint::PRISMATIC:
        out.kind = JointKind::prismatic;
        break;
      case urdf::Joint::FIXED:
        out.kind = JointKind::fixed;
        break;
      case urdf::Joint::FLOATING:
        return fail(line, where +
                              "type 'floating' is not supported (serial chains of "
                              "revolute, continuous, prismatic and fixed joints)");
      case urdf::Joint::PLANAR:
        return fail(line, where +
                              "type 'planar' is not supported (serial chains of "
                              "revolute, continuous, prismatic and fixed joints)");
      default:
        return fail(line, where + "unknown joint type");
    }
    if (j.mimic)
      return fail(line, where + "<mimic> is not supported (give every joint its own column)");
    if (out.movable()) {
      const Vec3 a{j.axis.x, j.axis.y, j.axis.z};
      const double n = norm(a);
      if (!(n > 0) || !std::isfinite(n))
        return fail(line, where + "<axis xyz> is zero or not finite");
      out.axis = a / n;
    }
    if (out.kind == JointKind::revolute || out.kind == JointKind::prismatic) {
      if (!j.limits)
        return fail(line, where + "<limit lower upper> is required for a " +
                              joint_kind_name(out.kind) + " joint");
      const double f = out.kind == JointKind::revolute ? 180.0 / std::numbers::pi : kMm;
      out.lower = j.limits->lower * f;
      out.upper = j.limits->upper * f;
      if (!(out.lower <= out.upper)) {
        return fail(line, where + "<limit>: lower " + short_number(j.limits->lower) + " > upper " +
                              short_number(j.limits->upper));
      }
    }
    return out;
  }
};

}  // namespace

Expected<Chain> parse_urdf(const std::string& text, const std::filesystem::path& file,
                           const UrdfOptions& options) {
  urdf::ModelInterfaceSharedPtr model;
  std::vector<std::string> messages;
  {
    std::lock_guard<std::mutex> lock(g_parse_mutex);
    Capture capture;
    console_bridge::useOutputHandler(&capture);
    try {
      model = urdf::parseURDF(text);
    } catch (const std::exception& e) {
      capture.messages.push_back(e.what());
    }
    console_bridge::restorePreviousOutputHandler();
    messages = std::move(capture.messages);
  }
  if (!model) {
    std::string why;
    std::int64_t line = -1;
    for (const std::string& m : messages) {
      why += (why.empty() ? "" : "; ") + m;
      if (line < 0) {
        const std::string n = bracketed(m);
        if (!n.empty()) {
          line = element_line(text, "joint", n);
          if (line < 0) line = element_line(text, "link", n);
        }
      }
    }
    return Error{.file = file.string(),
                 .line = line,
                 .reason = "not a valid URDF robot (urdfdom: " +
                           (why.empty() ? std::string("no message") : why) + ")"};
  }
  Reader r{text, file, options};
  Chain chain;
  chain.name = model->getName();
  chain.file = file.string();
  urdf::LinkConstSharedPtr l = model->getRoot();
  if (!l) return r.fail(-1, "no root link");
  while (true) {
    Expected<ChainLink> cl = r.link(*l);
    if (!cl) return cl.error();
    chain.links.push_back(std::move(*cl));
    if (l->child_joints.empty()) break;
    if (l->child_joints.size() > 1) {
      std::string names;
      for (const auto& j : l->child_joints) names += (names.empty() ? "" : ", ") + j->name;
      return r.fail(element_line(text, "link", l->name),
                    "link '" + l->name + "' has " + std::to_string(l->child_joints.size()) +
                        " child joints (" + names +
                        "): only serial chains are supported, not branches");
    }
    Expected<ChainJoint> j = r.joint(*l->child_joints[0]);
    if (!j) return j.error();
    if (j->movable()) chain.movable.push_back(chain.joints.size());
    chain.joints.push_back(std::move(*j));
    l = l->child_links.size() == 1 ? l->child_links[0] : model->getLink(chain.joints.back().child);
    if (!l) return r.fail(-1, "joint '" + chain.joints.back().name + "': child link not found");
  }
  return chain;
}

#endif  // INTERFERE_WITH_URDF

}  // namespace interfere::robot
