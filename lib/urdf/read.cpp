// Reading a URDF robot with simbob's own reader on pugixml (reader.h): one XML tree gives every
// value and the line of every element. The rules are urdfdom's, ROS's reference parser (what it
// requires, its defaults, its number syntax); the messages are simbob's, one line each at its
// element's line (docs/urdf.md, "How a URDF is read"). What simbob does not model (unknown
// elements and attributes, <transmission>, the rest of <gazebo>, <calibration>,
// <safety_controller>) becomes UrdfRobot::ignored, named once each.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "simbob/cr_math.h"
#include "simbob/values.h"
#include "scene/limits.h"
#include "urdf/reader.h"
#include "urdf/urdf.h"

namespace simbob {

// urdfdom's Rotation::setFromRPY and normalize (urdf_model/pose.h), term for term, but with the
// correctly rounded crSin and crCos: urdfdom's own calls go to libm, whose CPU-specific variants
// round a few angles differently (docs/ci.md, "Hinge angles and libm's atan2").
Quat quatFromRpy(double roll, double pitch, double yaw) {
  const double phi = roll / 2.0, the = pitch / 2.0, psi = yaw / 2.0;
  const double sphi = crSin(phi), cphi = crCos(phi), sthe = crSin(the), cthe = crCos(the);
  const double spsi = crSin(psi), cpsi = crCos(psi);
  double x = sphi * cthe * cpsi - cphi * sthe * spsi;
  double y = cphi * sthe * cpsi + sphi * cthe * spsi;
  double z = cphi * cthe * spsi - sphi * sthe * cpsi;
  double w = cphi * cthe * cpsi + sphi * sthe * spsi;
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  if (n == 0.0) return {1, 0, 0, 0};
  x /= n;
  y /= n;
  z /= n;
  w /= n;
  return {w, x, y, z};
}

const char* urdfJointTypeName(UrdfJoint::Type t) {
  switch (t) {
    case UrdfJoint::Revolute:
      return "revolute";
    case UrdfJoint::Continuous:
      return "continuous";
    case UrdfJoint::Prismatic:
      return "prismatic";
    case UrdfJoint::Fixed:
      return "fixed";
    case UrdfJoint::Floating:
      return "floating";
    case UrdfJoint::Planar:
      return "planar";
  }
  return "?";
}

namespace urdfread {

Reader::Reader(const std::string& text, const std::string& file, const UrdfPackages& packages, Diagnostics& diag)
    : text_(text), file_(file), packages_(packages), diag_(diag) {
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') newlines_.push_back(i);
}

namespace {

/// One field of <robot version="MAJOR.MINOR"> as urdfdom reads it (strtol, the whole text, not
/// negative); -1 where it refuses it.
long versionField(const std::string& s) {
  if (s.empty()) return -1;
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '\0' || v < 0) return -1;
  return v;
}

}  // namespace

/// <robot>: a name, and version 1.0 if it says one (urdfdom's rules).
bool Reader::readRobot(const pugi::xml_node& root) {
  if (!root.attribute("name")) {
    error(robot_->line, "<robot> needs name=\"...\"");
    return false;
  }
  robot_->name = root.attribute("name").value();
  if (const pugi::xml_attribute v = root.attribute("version")) {
    const std::string text = v.value();
    const size_t dot = text.find('.');
    const bool two = dot != std::string::npos && text.find('.', dot + 1) == std::string::npos;
    if (!two || versionField(text.substr(0, dot)) != 1 || versionField(text.substr(dot + 1)) != 0) {
      error(robot_->line, "<robot version=\"" + quoteInput(text, 40) + "\">: simbob reads URDF version 1.0 only");
      return false;
    }
  }
  return true;
}

/// The <texture> and <color> of a material, robot-level or inside a visual. A <color> needs four
/// numbers from 0 to 1, kept as urdfdom keeps them (single precision).
bool Reader::parseMaterial(const pugi::xml_node& m, const std::string& what, MaterialValues* out) {
  if (const pugi::xml_node t = m.child("texture"); t && t.attribute("filename")) {
    out->texture = t.attribute("filename").value();
    out->has_texture = true;
  }
  const pugi::xml_node c = m.child("color");
  if (!c) return true;
  double rgba[4];
  if (!required(c, "rgba", what) || !numbers(c, "rgba", what, 4, rgba)) return false;
  for (int k = 0; k < 4; ++k) {
    if (rgba[k] < 0 || rgba[k] > 1) {
      error(lineOf(c), what + ": <color rgba=\"" + quoteInput(c.attribute("rgba").value(), 80) +
                           "\">: " + formatNumber(rgba[k]) + " is outside [0, 1]");
      return false;
    }
    out->color[static_cast<size_t>(k)] = static_cast<double>(static_cast<float>(rgba[k]));
  }
  out->has_rgba = true;
  return true;
}

/// The robot-level <material> elements, in document order: each name once.
bool Reader::readMaterials(const pugi::xml_node& root) {
  bool ok = true;
  for (pugi::xml_node m : root.children("material")) {
    if (!required(m, "name", "robot '" + quoteInput(robot_->name) + "'")) {
      ok = false;
      continue;
    }
    const std::string name = m.attribute("name").value();
    if (auto twice = materials_.find(name); twice != materials_.end()) {
      error(lineOf(m), "material '" + quoteInput(name) + "' is defined twice (first at line " +
                           std::to_string(robot_->materials[static_cast<size_t>(twice->second)].line) + ")");
      ok = false;
      continue;
    }
    MaterialValues v;
    if (!parseMaterial(m, "material '" + quoteInput(name) + "'", &v)) {
      ok = false;
      continue;
    }
    UrdfMaterial out;
    out.name = name;
    out.line = lineOf(m);
    out.has_color = v.has_rgba;
    out.color = v.color;
    out.texture = v.texture;
    if (!out.texture.empty() && !resolveFile(out.texture, lineOf(m), "texture", &out.texture_path)) ok = false;
    materials_[name] = static_cast<int>(robot_->materials.size());
    material_values_[name] = v;
    robot_->materials.push_back(out);
  }
  return ok;
}

bool Reader::readInertial(const pugi::xml_node& in, const std::string& what, UrdfInertial* i) {
  i->line = lineOf(in);
  const std::string where = what + ": <inertial>";
  if (!origin(in, where, &i->origin)) return false;
  const pugi::xml_node mass = in.child("mass"), inertia = in.child("inertia");
  if (!mass || !inertia) {
    error(i->line, where + " needs <mass value=\"...\"> and <inertia ixx=\"...\" ...>");
    return false;
  }
  i->mass_line = lineOf(mass);
  i->inertia_line = lineOf(inertia);
  if (!required(mass, "value", what)) return false;
  const std::optional<double> m = number(mass, "value", what);
  if (!m) return false;
  i->mass = *m;
  static const char* const kNames[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  double v[6];
  for (int k = 0; k < 6; ++k) {
    if (!required(inertia, kNames[k], what)) return false;
    const std::optional<double> x = number(inertia, kNames[k], what);
    if (!x) return false;
    v[k] = *x;
  }
  i->inertia = {v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5]};
  return true;
}

/// A <visual> or <collision>: its origin and the first shape of its <geometry>.
bool Reader::readShape(const pugi::xml_node& x, const std::string& what, UrdfShape* out) {
  out->line = lineOf(x);
  if (!origin(x, what, &out->origin)) return false;
  const pugi::xml_node geometry = x.child("geometry");
  if (!geometry) {
    error(out->line, what + " needs <geometry>");
    return false;
  }
  pugi::xml_node shape;
  for (pugi::xml_node c : geometry.children())
    if (c.type() == pugi::node_element) {
      shape = c;
      break;
    }
  if (!shape) {
    error(lineOf(geometry), what + ": <geometry> holds no shape (<box>, <cylinder>, <sphere> or <mesh>)");
    return false;
  }
  out->shape_line = lineOf(shape);
  const std::string kind = shape.name();
  if (kind == "box") {
    out->kind = UrdfShape::Box;
    if (!required(shape, "size", what) || !numbers(shape, "size", what, 3, out->size.data())) return false;
  } else if (kind == "sphere") {
    out->kind = UrdfShape::Sphere;
    if (!required(shape, "radius", what)) return false;
    const std::optional<double> r = number(shape, "radius", what);
    if (!r) return false;
    out->size = {*r, 0, 0};
  } else if (kind == "cylinder") {
    out->kind = UrdfShape::Cylinder;
    if (!required(shape, "radius", what) || !required(shape, "length", what)) return false;
    const std::optional<double> length = number(shape, "length", what);
    const std::optional<double> r = length ? number(shape, "radius", what) : std::nullopt;
    if (!r) return false;
    out->size = {*r, *length, 0};
  } else if (kind == "mesh") {
    out->kind = UrdfShape::Mesh;
    if (!required(shape, "filename", what)) return false;
    out->filename = shape.attribute("filename").value();
    out->scale = {1, 1, 1};
    if (shape.attribute("scale") && !numbers(shape, "scale", what, 3, out->scale.data())) return false;
    return resolveFile(out->filename, out->shape_line, "mesh", &out->path);
  } else {
    error(out->shape_line, what + ": <geometry> holds <" + quoteInput(kind) +
                               ">, not a URDF shape (<box>, <cylinder>, <sphere> or <mesh>)");
    return false;
  }
  for (double s : out->size)
    if (!std::isfinite(s) || s < 0) {
      error(out->shape_line, "<" + kind + ">: sizes must be finite and >= 0");
      return false;
    }
  return true;
}

/// A visual's <material>, as urdfdom assigns it: the robot-level material of its name, or an
/// earlier visual's of that name, or else its own <color>/<texture> (which later visuals naming
/// it then get; not by an empty name). -1: none; -2: an error (*ok false).
int Reader::readVisualMaterial(const pugi::xml_node& visual, const std::string& what, bool* ok) {
  const pugi::xml_node m = visual.child("material");
  if (!m) return -1;
  MaterialValues own;
  if (!required(m, "name", what) || !parseMaterial(m, what + ": <material>", &own)) {
    *ok = false;
    return -2;
  }
  const std::string name = m.attribute("name").value();
  const MaterialValues* src = &own;
  if (name.empty()) {
    // urdfdom assigns nothing by an empty name (CAD exporters write name="" in every visual):
    // each such visual keeps its own colour or texture.
    if (!own.has_rgba && !own.has_texture) return -1;
  } else {
    auto known = material_values_.find(name);
    if (known == material_values_.end()) {
      if (!own.has_rgba && !own.has_texture) return -1;  // urdfdom: "material undefined", no material
      known = material_values_.emplace(name, own).first;
    }
    src = &known->second;
  }
  const MaterialValues& v = *src;
  auto it = materials_.find(name);
  const bool inline_def = m.child("color") || m.child("texture");
  if (!inline_def && it != materials_.end()) return it->second;
  UrdfMaterial out;
  out.name = name;
  out.line = lineOf(m);
  out.has_color = static_cast<bool>(m.child("color")) || it != materials_.end();
  out.color = v.color;
  out.texture = v.texture;
  if (!out.texture.empty() &&
      !resolveFile(out.texture, lineOf(m.child("texture") ? m.child("texture") : m), "texture", &out.texture_path)) {
    *ok = false;
    return -2;
  }
  robot_->materials.push_back(out);
  return static_cast<int>(robot_->materials.size()) - 1;
}

bool Reader::readLink(const pugi::xml_node& x) {
  if (!required(x, "name", "robot '" + quoteInput(robot_->name) + "'")) return false;
  UrdfLink l;
  l.name = x.attribute("name").value();
  l.line = lineOf(x);
  if (l.name.empty()) {  // its key would be the robot's own (issue 43): "duplicate key 'robot'"
    error(l.line, "robot '" + quoteInput(robot_->name) + "': a <link> with an empty name (name=\"\"): give it one");
    return false;
  }
  const std::string what = "link '" + quoteInput(l.name) + "'";
  if (auto twice = links_.find(l.name); twice != links_.end()) {
    error(l.line, what + " is defined twice (first at line " +
                      std::to_string(robot_->links[static_cast<size_t>(twice->second)].line) + ")");
    return false;
  }
  bool ok = true;
  if (const pugi::xml_node in = x.child("inertial")) {
    l.has_inertial = true;
    ok = readInertial(in, what, &l.inertial);
  }
  for (pugi::xml_node c : x.children()) {
    const bool visual = std::strcmp(c.name(), "visual") == 0;
    if (!visual && std::strcmp(c.name(), "collision") != 0) continue;
    UrdfShape s;
    const std::string where = what + ": <" + c.name() + ">";
    if (!readShape(c, where, &s)) {
      ok = false;
      continue;
    }
    if (visual) {
      s.material = readVisualMaterial(c, where, &ok);
      if (s.material == -2) continue;
      l.visuals.push_back(s);
    } else {
      l.collisions.push_back(s);
    }
  }
  // Named even when something in it is wrong: a joint naming it is not refused for that too.
  links_[l.name] = static_cast<int>(robot_->links.size());
  robot_->links.push_back(std::move(l));
  return ok;
}

bool Reader::readJointType(const pugi::xml_node& x, const std::string& what, UrdfJoint* j) {
  if (!required(x, "type", what)) return false;
  static const UrdfJoint::Type kTypes[] = {UrdfJoint::Revolute, UrdfJoint::Continuous, UrdfJoint::Prismatic,
                                           UrdfJoint::Fixed,    UrdfJoint::Floating,   UrdfJoint::Planar};
  const std::string type = x.attribute("type").value();
  std::vector<std::string> names;
  for (UrdfJoint::Type t : kTypes) {
    names.emplace_back(urdfJointTypeName(t));
    if (type == names.back()) {
      j->type = t;
      return true;
    }
  }
  const std::string near = didYouMean(type, names);
  error(j->line, what + ": unknown type '" + quoteInput(type, 40) + "'" +
                     (near.empty() ? "" : ", did you mean '" + near + "'?") +
                     " (revolute, continuous, prismatic, fixed, floating or planar)");
  return false;
}

/// <axis>, <limit>, <safety_controller>, <calibration>, <mimic> and <dynamics>: urdfdom's
/// defaults and what it requires of each.
bool Reader::readJointParts(const pugi::xml_node& x, const std::string& what, UrdfJoint* j, std::string* leader) {
  // The axis of a fixed or floating joint is not read (urdfdom leaves it 0 0 0).
  j->axis = {0, 0, 0};
  const pugi::xml_node axis = x.child("axis");
  j->axis_line = axis ? lineOf(axis) : j->line;
  if (j->type != UrdfJoint::Fixed && j->type != UrdfJoint::Floating) {
    if (!axis) j->axis = {1, 0, 0};
    if (axis && axis.attribute("xyz") && !numbers(axis, "xyz", what, 3, j->axis.data())) return false;
  }
  if (const pugi::xml_node limit = x.child("limit")) {
    j->has_limit = true;
    j->limit_line = lineOf(limit);
    if (!numberIf(limit, "lower", what, &j->lower) || !numberIf(limit, "upper", what, &j->upper)) return false;
    if (!required(limit, "effort", what) || !numberIf(limit, "effort", what, &j->effort)) return false;
    if (!required(limit, "velocity", what) || !numberIf(limit, "velocity", what, &j->velocity)) return false;
  } else if (j->type == UrdfJoint::Revolute || j->type == UrdfJoint::Prismatic) {
    error(j->line,
          what + ": a " + urdfJointTypeName(j->type) + " joint needs <limit> (lower, upper, effort, velocity)");
    return false;
  }
  double unused = 0;
  if (const pugi::xml_node safety = x.child("safety_controller")) {
    if (!numberIf(safety, "soft_lower_limit", what, &unused) || !numberIf(safety, "soft_upper_limit", what, &unused) ||
        !numberIf(safety, "k_position", what, &unused) || !required(safety, "k_velocity", what) ||
        !numberIf(safety, "k_velocity", what, &unused))
      return false;
  }
  if (const pugi::xml_node calibration = x.child("calibration")) {
    if (!numberIf(calibration, "rising", what, &unused) || !numberIf(calibration, "falling", what, &unused))
      return false;
  }
  if (const pugi::xml_node mimic = x.child("mimic")) {
    j->mimic_line = lineOf(mimic);
    if (!required(mimic, "joint", what)) return false;
    *leader = mimic.attribute("joint").value();
    j->multiplier = 1;
    j->offset = 0;
    if (!numberIf(mimic, "multiplier", what, &j->multiplier) || !numberIf(mimic, "offset", what, &j->offset))
      return false;
  }
  if (const pugi::xml_node dynamics = x.child("dynamics")) {
    j->dynamics_line = lineOf(dynamics);
    if (!dynamics.attribute("damping") && !dynamics.attribute("friction")) {
      error(j->dynamics_line, what + ": <dynamics> needs damping=\"...\" or friction=\"...\"");
      return false;
    }
    if (!numberIf(dynamics, "damping", what, &j->damping) || !numberIf(dynamics, "friction", what, &j->friction))
      return false;
  }
  return true;
}

/// A joint's <parent link> or <child link>: a link of the robot.
bool Reader::readJointLink(const pugi::xml_node& x, const char* which, const std::string& what, int* out) {
  const pugi::xml_node e = x.child(which);
  if (!e || !e.attribute("link")) {
    error(lineOf(x), what + " needs <" + which + " link=\"...\">");
    return false;
  }
  auto it = links_.find(e.attribute("link").value());
  if (it == links_.end()) {
    error(lineOf(e), what + ": <" + which + "> names no link '" + quoteInput(e.attribute("link").value()) +
                         "' (every link a joint names is a <link> of the robot)");
    return false;
  }
  *out = it->second;
  return true;
}

bool Reader::readJoint(const pugi::xml_node& x) {
  if (!required(x, "name", "robot '" + quoteInput(robot_->name) + "'")) return false;
  UrdfJoint j;
  j.name = x.attribute("name").value();
  j.line = lineOf(x);
  if (j.name.empty()) {  // its key would be the robot's own (issue 43): "duplicate key 'robot'"
    error(j.line, "robot '" + quoteInput(robot_->name) + "': a <joint> with an empty name (name=\"\"): give it one");
    return false;
  }
  const std::string what = "joint '" + quoteInput(j.name) + "'";
  if (auto twice = joints_.find(j.name); twice != joints_.end()) {
    error(j.line, what + " is defined twice (first at line " +
                      std::to_string(robot_->joints[static_cast<size_t>(twice->second)].line) + ")");
    return false;
  }
  std::string leader;
  if (!origin(x, what, &j.origin) || !readJointType(x, what, &j) || !readJointParts(x, what, &j, &leader) ||
      !readJointLink(x, "parent", what, &j.parent) || !readJointLink(x, "child", what, &j.child))
    return false;
  for (double v : j.axis)  // a direction of 1e308 overflows its length: say which number is too large
    if (!range(j.axis_line, what + ": <axis> xyz", v)) return false;
  const double n = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
  const bool moves = j.type == UrdfJoint::Revolute || j.type == UrdfJoint::Continuous || j.type == UrdfJoint::Prismatic;
  if (moves && !(n > 1e-9 && std::isfinite(n))) {
    error(j.axis_line, what + ": <axis> must be a non-zero direction");
    return false;
  }
  if (moves && n != 1.0) j.axis = {j.axis[0] / n, j.axis[1] / n, j.axis[2] / n};
  joints_[j.name] = static_cast<int>(robot_->joints.size());
  if (j.mimic_line) mimics_.push_back({static_cast<int>(robot_->joints.size()), leader});
  robot_->joints.push_back(j);
  return true;
}

/// The links and joints make one tree: each link the child of one joint at most, one root (the
/// link that is no joint's child) and every link reached from it.
bool Reader::checkTree() {
  const size_t n = robot_->links.size();
  std::vector<int> parent_joint(n, -1);
  std::vector<std::vector<int>> children(n);
  for (size_t ji = 0; ji < robot_->joints.size(); ++ji) {
    const UrdfJoint& j = robot_->joints[ji];
    int& pj = parent_joint[static_cast<size_t>(j.child)];
    if (pj >= 0) {
      const UrdfJoint& first = robot_->joints[static_cast<size_t>(pj)];
      error(j.line, "joint '" + quoteInput(j.name) + "': link '" +
                        quoteInput(robot_->links[static_cast<size_t>(j.child)].name) +
                        "' is already the child of joint '" + quoteInput(first.name) + "' (line " +
                        std::to_string(first.line) + "): in a URDF tree each link has one parent joint");
      return false;
    }
    pj = static_cast<int>(ji);
    children[static_cast<size_t>(j.parent)].push_back(j.child);
  }
  int root = -1;
  for (size_t l = 0; l < n; ++l) {
    if (parent_joint[l] >= 0) continue;
    if (root >= 0) {
      const UrdfLink& first = robot_->links[static_cast<size_t>(root)];
      error(robot_->links[l].line, "link '" + quoteInput(robot_->links[l].name) + "' is a second root beside '" +
                                       quoteInput(first.name) + "' (line " + std::to_string(first.line) +
                                       "): no joint has it as child, and a URDF is one tree with one root link");
      return false;
    }
    root = static_cast<int>(l);
  }
  if (root < 0) {
    error(robot_->line, "robot '" + quoteInput(robot_->name) +
                            "' has no root link: every link is some joint's child (its joints make a loop)");
    return false;
  }
  std::vector<char> reached(n, 0);
  std::vector<int> todo{root};
  reached[static_cast<size_t>(root)] = 1;
  while (!todo.empty()) {
    const int l = todo.back();
    todo.pop_back();
    for (int c : children[static_cast<size_t>(l)])
      if (!reached[static_cast<size_t>(c)]) {
        reached[static_cast<size_t>(c)] = 1;
        todo.push_back(c);
      }
  }
  for (size_t l = 0; l < n; ++l)
    if (!reached[l]) {
      error(robot_->links[l].line, "link '" + quoteInput(robot_->links[l].name) + "' is not connected to the root '" +
                                       quoteInput(robot_->links[static_cast<size_t>(root)].name) +
                                       "': its joints make a loop");
      return false;
    }
  robot_->root = root;
  return true;
}

std::shared_ptr<const UrdfRobot> Reader::read() {
  robot_->file = file_;
  pugi::xml_parse_result res = doc_.load_buffer(text_.data(), text_.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!res && res.status == pugi::status_no_document_element) {
    error(1, "not a URDF file: no <robot> element");
    return nullptr;
  }
  if (!res) {
    auto off = static_cast<size_t>(std::max<ptrdiff_t>(0, res.offset));
    error(static_cast<int>(std::upper_bound(newlines_.begin(), newlines_.end(), off) - newlines_.begin()) + 1,
          std::string("malformed XML: ") + res.description());
    return nullptr;
  }
  pugi::xml_node root = doc_.document_element();
  if (!root) {
    error(1, "not a URDF file: no <robot> element");
    return nullptr;
  }
  robot_->line = lineOf(root);
  if (std::strcmp(root.name(), "robot") != 0) {
    error(robot_->line, "root element is <" + quoteInput(root.name()) + ">, expected <robot>" +
                            (std::strcmp(root.name(), "world") == 0
                                 ? " (a URDF <world> is not read: import each robot with an RCImportURDF)"
                                 : ""));
    return nullptr;
  }
  if (!checkDepth(root) || !readRobot(root)) return nullptr;
  walk(root, "robot");
  // urdfdom's order: the materials, the links, the joints, then the tree.
  bool ok = readMaterials(root);
  for (pugi::xml_node x : root.children("link")) ok = readLink(x) && ok;
  if (robot_->links.empty() && ok) {
    error(robot_->line, "robot '" + quoteInput(robot_->name) + "' has no <link>");
    return nullptr;
  }
  for (pugi::xml_node x : root.children("joint")) ok = readJoint(x) && ok;
  if (!ok || !checkTree()) return finish(false);
  for (const auto& [ji, leader] : mimics_) {
    auto it = joints_.find(leader);
    UrdfJoint& j = robot_->joints[static_cast<size_t>(ji)];
    if (it == joints_.end()) {
      error(j.mimic_line, "joint '" + quoteInput(j.name) + "': <mimic> names no joint '" + quoteInput(leader) + "'");
      ok = false;
    } else {
      j.mimic = it->second;
    }
  }
  ok = ok && mimicsAcyclic();
  for (pugi::xml_node g : root.children("gazebo")) ok = readGazebo(g, links_, joints_) && ok;
  ok = checkValues() && ok;
  return finish(ok);
}

/// The robot, or null after an error; a package found nowhere is said once, at its first name.
std::shared_ptr<const UrdfRobot> Reader::finish(bool ok) {
  std::vector<Missing> missing;
  for (const auto& [package, m] : missing_) missing.push_back(m);
  std::sort(missing.begin(), missing.end(), [](const Missing& a, const Missing& b) { return a.line < b.line; });
  for (const Missing& m : missing)
    error(m.line, m.message + (m.count > 1 ? " (" + std::to_string(m.count) + " names in this package)" : ""),
          ErrorKind::MissingInput);
  if (!ok || !missing.empty()) return nullptr;
  return robot_;
}

// A URDF number passes the checks a scene file's parameter gets (lib/scene/params.cpp): finite,
// within kMaxValueMagnitude, and >= 0 where a negative value has no meaning. Past them, ODE's
// inertia and contact math overflow (a mass of 1e200 ends in an ODE assertion).
// A joint that mimics itself, or joints that mimic each other round a loop, have no leader to
// follow (issue 43): refused at the <mimic> line of the first joint of the loop, naming it.
bool Reader::mimicsAcyclic() {
  const std::vector<UrdfJoint>& joints = robot_->joints;
  std::vector<char> state(joints.size(), 0);  // 0 unseen, 1 on the current path, 2 done
  for (size_t start = 0; start < joints.size(); ++start) {
    std::vector<size_t> path;
    size_t j = start;
    while (state[j] == 0) {
      state[j] = 1;
      path.push_back(j);
      if (joints[j].mimic < 0) break;
      j = static_cast<size_t>(joints[j].mimic);
    }
    if (state[j] == 1 && joints[j].mimic >= 0) {  // back on the current path: a loop from j
      std::string loop = "'" + quoteInput(joints[j].name) + "'";
      for (size_t k = static_cast<size_t>(joints[j].mimic); k != j; k = static_cast<size_t>(joints[k].mimic))
        loop += " -> '" + quoteInput(joints[k].name) + "'";
      error(joints[j].mimic_line,
            "joint '" + quoteInput(joints[j].name) + "': <mimic> " +
                (joints[j].mimic == static_cast<int>(j)
                     ? std::string("follows the joint itself")
                     : "joints follow each other round a loop (" + loop + " -> '" + quoteInput(joints[j].name) + "')") +
                ": a mimic joint needs a leader that moves of its own");
      return false;
    }
    for (size_t k : path) state[k] = 2;
  }
  return true;
}

bool Reader::range(int line, const std::string& what, double v, bool non_negative) {
  if (!std::isfinite(v)) {
    error(line, what + " " + formatNumber(v) + " must be finite");
    return false;
  }
  if (std::fabs(v) > kMaxValueMagnitude) {
    error(line, what + " " + formatNumber(v) + " is beyond the supported magnitude " +
                    formatNumber(kMaxValueMagnitude) + " (the limit of every number of a scene)");
    return false;
  }
  if (non_negative && v < 0) {
    error(line, what + " " + formatNumber(v) + " must be >= 0");
    return false;
  }
  return true;
}

// Every number read, through range(): each problem said at its element's line.
bool Reader::checkValues() {
  bool ok = true;
  // One message for an element: its first number that fails.
  auto all = [&](int line, const std::string& what, auto const& values, bool non_negative = false) {
    for (double v : values)
      if (!range(line, what, v, non_negative)) {
        ok = false;
        return;
      }
  };
  auto position = [&](int line, const std::string& what, const Transform& t) {
    all(line, what + ": <origin> xyz", t.p);
  };
  auto shapes = [&](const std::string& link, const std::vector<UrdfShape>& list, const char* kind) {
    for (const UrdfShape& sh : list) {
      const std::string what = "link '" + quoteInput(link) + "': <" + kind + ">";
      position(sh.line, what, sh.origin);
      all(sh.shape_line, what + " size", sh.size, true);
      if (sh.kind == UrdfShape::Mesh) all(sh.shape_line, what + " <mesh> scale", sh.scale);
    }
  };
  for (const UrdfLink& l : robot_->links) {
    const std::string what = "link '" + quoteInput(l.name) + "'";
    if (l.has_inertial) {
      const UrdfInertial& i = l.inertial;
      position(i.line, what + ": <inertial>", i.origin);
      ok = range(i.mass_line, what + ": <mass>", i.mass) && ok;
      all(i.inertia_line, what + ": <inertia>", i.inertia);
    }
    shapes(l.name, l.visuals, "visual");
    shapes(l.name, l.collisions, "collision");
  }
  for (const UrdfJoint& j : robot_->joints) {
    const std::string what = "joint '" + quoteInput(j.name) + "'";
    position(j.line, what, j.origin);
    if (j.has_limit) {
      ok = range(j.limit_line, what + ": <limit> lower", j.lower) && ok;
      ok = range(j.limit_line, what + ": <limit> upper", j.upper) && ok;
      ok = range(j.limit_line, what + ": <limit> effort", j.effort, true) && ok;
      ok = range(j.limit_line, what + ": <limit> velocity", j.velocity, true) && ok;
    }
    if (j.dynamics_line) {
      ok = range(j.dynamics_line, what + ": <dynamics> damping", j.damping, true) && ok;
      ok = range(j.dynamics_line, what + ": <dynamics> friction", j.friction, true) && ok;
    }
    if (j.mimic_line) {
      ok = range(j.mimic_line, what + ": <mimic> multiplier", j.multiplier) && ok;
      ok = range(j.mimic_line, what + ": <mimic> offset", j.offset) && ok;
    }
  }
  return ok;
}

}  // namespace urdfread

std::shared_ptr<const UrdfRobot> readUrdf(const std::string& text, const std::string& file,
                                          const UrdfPackages& packages, Diagnostics& diag) {
  urdfread::Reader r(text, file, packages, diag);
  return r.read();
}

bool looksLikeUrdf(const std::string& name, const std::string& text) {
  const size_t n = name.size();
  if (n >= 5 && equalsIgnoreCase(std::string_view(name).substr(n - 5), ".urdf")) return true;
  // The first element: skip the declaration, comments and a DOCTYPE.
  size_t i = 0;
  while ((i = text.find('<', i)) != std::string::npos) {
    if (text.compare(i, 4, "<!--") == 0) {
      i = text.find("-->", i);
      if (i == std::string::npos) return false;
      continue;
    }
    if (text.compare(i, 2, "<?") == 0 || text.compare(i, 2, "<!") == 0) {
      ++i;
      continue;
    }
    const size_t e = text.find_first_of(" \t\r\n/>", i + 1);
    return text.compare(i + 1, e == std::string::npos ? std::string::npos : e - i - 1, "robot") == 0;
  }
  return false;
}

}  // namespace simbob
