// Reading a URDF robot: urdfdom parses the values; pugixml reads the same text again for the line
// of every element (urdfdom keeps none), for the <gazebo reference> tags Gazebo classic hands to
// ODE (UrdfGazebo) and for what urdfdom drops without a word (unknown elements and attributes,
// <transmission>, the rest of <gazebo>, <calibration>, <safety_controller>), which become
// UrdfRobot::ignored, named once each.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <pugixml.hpp>
#include <locale>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "simbob/cr_math.h"
#include "simbob/values.h"
#include "simbob/tool/platform.h"
#include "scene/limits.h"
#include "urdf/paths.h"
#include "urdf/urdf.h"
#include "urdf/urdf_module.h"

// Weak: defined only where urdfdom_parse.cpp is linked in (the Python module); null elsewhere.
extern "C" const simbob::UrdfModule* simbob_urdf_module() __attribute__((weak));

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

namespace {

/// The module's table, or nullptr with `why` set. A program that links urdfdom_parse.cpp in (the
/// Python module) has simbob_urdf_module() itself; others open libsimbob_urdf.so.
const UrdfModule* urdfModule(std::string* why) {
  return simbobModule<UrdfModule>("libsimbob_urdf.so", "SIMBOB_URDF_MODULE", "simbob_urdf_module", kUrdfModuleAbi,
                                  "reading URDF needs libsimbob_urdf.so (urdfdom)", &simbob_urdf_module, why);
}

class Reader {
 public:
  Reader(const std::string& text, const std::string& file, const UrdfPackages& packages, Diagnostics& diag)
      : text_(text), file_(file), packages_(packages), diag_(diag) {
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') newlines_.push_back(i);
  }

  std::shared_ptr<const UrdfRobot> read();

 private:
  int lineOf(const pugi::xml_node& n) const {
    const auto off = static_cast<size_t>(std::max<ptrdiff_t>(0, n.offset_debug()));
    return static_cast<int>(std::upper_bound(newlines_.begin(), newlines_.end(), off) - newlines_.begin()) + 1;
  }
  void error(int line, const std::string& msg, ErrorKind kind = ErrorKind::InvalidInput) {
    diag_.error({file_, line}, msg, kind);
  }
  void ignore(int line, const std::string& what) {
    // A map, not a search of the notes: a file may hold 200,000 different unknown elements.
    auto [it, added] = ignored_index_.emplace(what, robot_->ignored.size());
    if (!added) {
      ++robot_->ignored[it->second].count;
      return;
    }
    robot_->ignored.push_back({line, what, 1});
  }
  int urdfdomLine(const std::string& message) const;
  void walk(const pugi::xml_node& n, const std::string& path);
  bool readLink(const pugi::xml_node& x, const urdf::Link& u);
  bool readShape(const pugi::xml_node& x, const urdf::Geometry& g, const urdf::Pose& origin, UrdfShape* out);
  int readVisualMaterial(const pugi::xml_node& visual, const urdf::Visual& v);
  bool readJoint(const pugi::xml_node& x, const urdf::Joint& u, const std::map<std::string, int>& links);
  bool resolveFile(const std::string& name, int line, const char* what, std::string* path);
  bool checkDepth(const pugi::xml_node& root);
  bool readGazebo(const pugi::xml_node& g, const std::map<std::string, int>& links,
                  const std::map<std::string, int>& joints);
  bool gazeboNumber(const pugi::xml_node& tag, const std::string& what, double lo, bool lo_open, UrdfTag* out);
  bool gazeboBool(const pugi::xml_node& tag, const std::string& what, bool invert, UrdfTag* out);
  bool number(int line, const std::string& what, double v, bool non_negative = false);
  bool checkValues();

  const std::string& text_;
  std::string file_;
  const UrdfPackages& packages_;
  Diagnostics& diag_;
  std::vector<size_t> newlines_;
  pugi::xml_document doc_;
  std::shared_ptr<UrdfRobot> robot_ = std::make_shared<UrdfRobot>();
  std::map<std::string, int> materials_;                   // robot-level material name -> index
  std::unordered_map<std::string, size_t> ignored_index_;  // note text -> UrdfRobot::ignored index
  std::vector<std::pair<int, std::string>> mimics_;        // joint index, the joint it follows
  struct Missing {
    int line;
    std::string message;
    int count;
  };
  std::map<std::string, Missing> missing_;  // package:// prefix -> its first name
};

bool finite(const Transform& t) {
  for (double v : t.p)
    if (!std::isfinite(v)) return false;
  for (double v : t.q)
    if (!std::isfinite(v)) return false;
  return true;
}

// The transform of an <origin> as urdfdom parsed it into p; `element` holds the <origin> (a
// <joint>, <visual>, <collision> or <inertial>). Its rotation is computed again from the rpy
// text, read as urdfdom reads it (space-separated, the C locale), with quatFromRpy.
Transform toTransform(const urdf::Pose& p, const pugi::xml_node& element) {
  Transform t;
  t.p = {p.position.x, p.position.y, p.position.z};
  t.q = {p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z};
  const pugi::xml_attribute rpy = element.child("origin").attribute("rpy");
  if (!rpy) return t;
  std::istringstream in(rpy.value());
  in.imbue(std::locale::classic());
  double v[3];
  int n = 0;
  std::string piece;
  while (in >> piece) {
    std::istringstream one(piece);
    one.imbue(std::locale::classic());
    if (n == 3 || !(one >> v[n])) return t;  // urdfdom refused it, or read it otherwise: keep its value
    ++n;
  }
  if (n == 3) t.q = quatFromRpy(v[0], v[1], v[2]);
  return t;
}

// The URDF elements simbob reads, with their attributes; anything else is named as ignored.
struct Known {
  const char* path;   // element path below <robot>, '/' separated
  const char* attrs;  // space-separated attribute names
};
constexpr Known kKnown[] = {
    {"robot", "name version"},
    {"robot/link", "name"},
    {"robot/link/inertial", ""},
    {"robot/link/inertial/origin", "xyz rpy"},
    {"robot/link/inertial/mass", "value"},
    {"robot/link/inertial/inertia", "ixx ixy ixz iyy iyz izz"},
    {"robot/link/visual", "name"},
    {"robot/link/visual/origin", "xyz rpy"},
    {"robot/link/visual/geometry", ""},
    {"robot/link/visual/geometry/box", "size"},
    {"robot/link/visual/geometry/sphere", "radius"},
    {"robot/link/visual/geometry/cylinder", "radius length"},
    {"robot/link/visual/geometry/mesh", "filename scale"},
    {"robot/link/visual/material", "name"},
    {"robot/link/visual/material/color", "rgba"},
    {"robot/link/visual/material/texture", "filename"},
    {"robot/link/collision", "name"},
    {"robot/link/collision/origin", "xyz rpy"},
    {"robot/link/collision/geometry", ""},
    {"robot/link/collision/geometry/box", "size"},
    {"robot/link/collision/geometry/sphere", "radius"},
    {"robot/link/collision/geometry/cylinder", "radius length"},
    {"robot/link/collision/geometry/mesh", "filename scale"},
    {"robot/material", "name"},
    {"robot/material/color", "rgba"},
    {"robot/material/texture", "filename"},
    {"robot/joint", "name type"},
    {"robot/joint/origin", "xyz rpy"},
    {"robot/joint/parent", "link"},
    {"robot/joint/child", "link"},
    {"robot/joint/axis", "xyz"},
    {"robot/joint/limit", "lower upper effort velocity"},
    {"robot/joint/dynamics", "damping friction"},
    {"robot/joint/mimic", "joint multiplier offset"},
    {"robot/gazebo", "reference"},
};

// Elements URDF defines that simbob does not model, with the reason given once.
struct Unmodelled {
  const char* name;
  const char* why;
};
constexpr Unmodelled kUnmodelled[] = {
    {"transmission", "simbob models no transmissions; RCImportURDF's Drives puts a drive on every movable joint"},
    {"calibration", "joint positions are zero at the URDF's zero configuration"},
    {"safety_controller", "simbob has no safety controllers; the <limit> is what stops a joint"},
};

bool hasWord(const char* words, const char* w) {
  const size_t n = std::strlen(w);
  for (const char* p = words; *p;) {
    const char* e = std::strchr(p, ' ');
    const size_t len = e ? static_cast<size_t>(e - p) : std::strlen(p);
    if (len == n && std::strncmp(p, w, n) == 0) return true;
    if (!e) break;
    p = e + 1;
  }
  return false;
}

void Reader::walk(const pugi::xml_node& n, const std::string& path) {
  const Known* known = nullptr;
  for (const Known& k : kKnown)
    if (path == k.path) known = &k;
  if (!known) {
    for (const Unmodelled& u : kUnmodelled)
      if (std::strcmp(n.name(), u.name) == 0) {
        ignore(lineOf(n), "<" + std::string(u.name) + "> ignored: " + u.why);
        return;
      }
    ignore(lineOf(n),
           "<" + quoteInput(n.name()) + "> ignored: not an element of URDF" +
               (path.find('/') == std::string::npos ? "" : " inside <" + path.substr(0, path.rfind('/')) + ">"));
    return;
  }
  for (pugi::xml_attribute a = n.first_attribute(); a; a = a.next_attribute()) {
    const std::string name = a.name();
    if (hasWord(known->attrs, a.name()) || name.rfind("xmlns", 0) == 0) continue;
    ignore(lineOf(n), "attribute '" + quoteInput(name) + "' of <" + n.name() + "> ignored");
  }
  if (path == "robot/gazebo") return;  // its tags: readGazebo
  int shapes = 0;
  for (pugi::xml_node c : n.children()) {
    if (c.type() != pugi::node_element) continue;
    if (std::strcmp(n.name(), "geometry") == 0 && ++shapes == 2)
      ignore(lineOf(c), "<geometry> with more than one shape: only the first is used");
    walk(c, path + "/" + c.name());
  }
}

int Reader::urdfdomLine(const std::string& message) const {
  // A value urdfdom cannot read ("Unable to parse component [abc] to a double"): the element
  // whose attribute holds it.
  const size_t open = message.find('['), close = message.find(']', open == std::string::npos ? 0 : open);
  if (message.find("parse") != std::string::npos && open != std::string::npos && close != std::string::npos) {
    const std::string token = message.substr(open + 1, close - open - 1);
    std::vector<pugi::xml_node> todo{doc_.document_element()};
    while (!token.empty() && !todo.empty()) {
      pugi::xml_node n = todo.back();
      todo.pop_back();
      for (pugi::xml_attribute a = n.first_attribute(); a; a = a.next_attribute())
        if (std::string(a.value()).find(token) != std::string::npos) return lineOf(n);
      for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling())
        if (c.type() == pugi::node_element) todo.push_back(c);
    }
  }
  // urdfdom names the link or joint it stopped at ("Joint [j1] ...", "link 'l' ..."): find it.
  int best = 0;
  for (pugi::xml_node c : doc_.document_element().children()) {
    const char* name = c.attribute("name").value();
    if (!*name) continue;
    const std::string n(name);
    if (message.find("[" + n + "]") != std::string::npos || message.find("'" + n + "'") != std::string::npos ||
        message.find("\"" + n + "\"") != std::string::npos)
      return lineOf(c);
    if (!best && message.find(n) != std::string::npos && n.size() > 2) best = lineOf(c);
  }
  return best ? best : lineOf(doc_.document_element());
}

// --- <gazebo>: what Gazebo classic's URDF converter (sdformat's parser_urdf.cc) hands to ODE -----

/// A tag's text as Gazebo reads it: its `value` attribute, or else its text, without blanks around.
std::string gazeboText(const pugi::xml_node& tag) {
  std::string t = tag.attribute("value") ? tag.attribute("value").value() : tag.child_value();
  const size_t b = t.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return t.substr(b, t.find_last_not_of(" \t\r\n") - b + 1);
}

bool Reader::gazeboNumber(const pugi::xml_node& tag, const std::string& what, double lo, bool lo_open, UrdfTag* out) {
  const std::string text = gazeboText(tag);
  const std::optional<double> v = parseNumber(text);
  const int line = lineOf(tag);
  if (!v) {
    error(line, what + ": <" + tag.name() + "> '" + quoteInput(text, 80) + "' is not a number");
    return false;
  }
  if (!std::isfinite(*v) || (lo_open ? !(*v > lo) : !(*v >= lo))) {
    error(line, what + ": <" + tag.name() + "> " + formatNumber(*v) + " must be finite and " +
                    (lo_open ? "> " : ">= ") + formatNumber(lo));
    return false;
  }
  if (!number(line, what + ": <" + tag.name() + ">", *v)) return false;
  *out = {line, *v};
  return true;
}

bool Reader::gazeboBool(const pugi::xml_node& tag, const std::string& what, bool invert, UrdfTag* out) {
  const std::string text = gazeboText(tag);
  bool v;
  if (equalsIgnoreCase(text, "true") || equalsIgnoreCase(text, "yes") || text == "1") {
    v = true;
  } else if (equalsIgnoreCase(text, "false") || equalsIgnoreCase(text, "no") || text == "0") {
    v = false;
  } else {
    error(lineOf(tag), what + ": <" + tag.name() + "> '" + quoteInput(text, 80) + "' is not true or false");
    return false;
  }
  *out = {lineOf(tag), (v != invert) ? 1.0 : 0.0};
  return true;
}

/// One <gazebo> element. With reference="LINK": the tags Gazebo classic maps onto the link's ODE
/// surface and body (docs/urdf.md, "Surfaces"); without reference: the robot's <self_collide>;
/// every other tag is named once as ignored.
bool Reader::readGazebo(const pugi::xml_node& g, const std::map<std::string, int>& links,
                        const std::map<std::string, int>& joints) {
  const pugi::xml_attribute ref = g.attribute("reference");
  bool ok = true;
  auto children = [&](auto&& each) {
    for (pugi::xml_node c : g.children())
      if (c.type() == pugi::node_element) each(c, std::string(c.name()));
  };
  if (!ref) {
    children([&](const pugi::xml_node& c, const std::string& name) {
      if (name == "self_collide") {
        ok = gazeboBool(c, "robot '" + robot_->name + "'", false, &robot_->self_collide) && ok;
      } else if (name == "selfCollide") {
        ignore(lineOf(c),
               "<gazebo> <selfCollide> without reference ignored: Gazebo classic applies it to a link "
               "(<gazebo reference=\"LINK\">); <self_collide> applies to every link");
      } else if (name == "static") {
        ignore(lineOf(c), "<gazebo> <static> ignored: FixedBase fixes the root link to the world");
      } else if (name == "plugin") {
        ignore(lineOf(c),
               "<gazebo> <plugin> ignored: simbob runs no Gazebo plug-ins (RCImportURDF's Drives puts "
               "a drive on every movable joint)");
      } else {
        ignore(lineOf(c), "<gazebo> <" + quoteInput(name) + "> without reference ignored: not read by simbob");
      }
    });
    return ok;
  }
  const std::string target = ref.value();
  auto link = links.find(target);
  if (link == links.end()) {
    if (joints.count(target)) {
      children([&](const pugi::xml_node& c, const std::string& name) {
        ignore(lineOf(c), "<gazebo> <" + quoteInput(name) +
                              "> of a joint ignored: simbob reads no joint tags of "
                              "Gazebo");
      });
    } else {
      diag_.warning({file_, lineOf(g)}, "<gazebo reference=\"" + quoteInput(target) +
                                            "\"> names no link or joint of the robot: its tags are ignored");
    }
    return true;
  }
  UrdfLink& l = robot_->links[static_cast<size_t>(link->second)];
  UrdfGazebo& gz = l.gazebo;
  const std::string what = "link '" + l.name + "'";
  children([&](const pugi::xml_node& c, const std::string& name) {
    if (name == "mu1") {
      ok = gazeboNumber(c, what, 0, false, &gz.mu1) && ok;
    } else if (name == "mu2") {
      ok = gazeboNumber(c, what, 0, false, &gz.mu2) && ok;
    } else if (name == "kp") {
      ok = gazeboNumber(c, what, 0, true, &gz.kp) && ok;
    } else if (name == "kd") {
      ok = gazeboNumber(c, what, 0, false, &gz.kd) && ok;
    } else if (name == "minDepth") {
      ok = gazeboNumber(c, what, 0, false, &gz.min_depth) && ok;
    } else if (name == "maxVel") {
      ok = gazeboNumber(c, what, 0, false, &gz.max_vel) && ok;
    } else if (name == "maxContacts") {
      UrdfTag t;
      if (!gazeboNumber(c, what, 1, false, &t)) {
        ok = false;
      } else if (t.value != std::floor(t.value) || t.value > 1e6) {
        error(t.line, what + ": <maxContacts> " + formatNumber(t.value) + " must be a whole number from 1 to 1000000");
        ok = false;
      } else {
        gz.max_contacts = t;
      }
    } else if (name == "fdir1") {
      std::string problem;
      const std::string text = gazeboText(c);
      const auto v = parseNumberList(text, &problem);
      if (!v || v->size() != 3 || !std::isfinite((*v)[0]) || !std::isfinite((*v)[1]) || !std::isfinite((*v)[2])) {
        error(lineOf(c), what + ": <fdir1> '" + quoteInput(text, 80) + "' must be three finite numbers");
        ok = false;
      } else {
        gz.fdir1_tag = {lineOf(c), 0};
        gz.fdir1 = {(*v)[0], (*v)[1], (*v)[2]};
      }
    } else if (name == "selfCollide") {
      ok = gazeboBool(c, what, false, &gz.self_collide) && ok;
    } else if (name == "gravity") {
      ok = gazeboBool(c, what, false, &gz.gravity) && ok;
    } else if (name == "turnGravityOff") {
      ok = gazeboBool(c, what, true, &gz.gravity) && ok;
    } else if (name == "material") {
      ignore(lineOf(c),
             "<gazebo> <material> ignored: Gazebo's material scripts are not read (a link's colour is "
             "its URDF <material>)");
    } else if (name == "plugin") {
      ignore(lineOf(c),
             "<gazebo> <plugin> ignored: simbob runs no Gazebo plug-ins (RCImportURDF's Drives puts a "
             "drive on every movable joint)");
    } else if (name == "sensor") {
      ignore(lineOf(c),
             "<gazebo> <sensor> ignored: Gazebo's sensors are not read (simbob's sensors go on the "
             "link's key)");
    } else {
      ignore(lineOf(c), "<gazebo> <" + quoteInput(name) +
                            "> of a link ignored: not one of the surface tags simbob reads (docs/urdf.md)");
    }
  });
  return ok;
}

/// Refuses a tree deeper than kMaxUrdfDepth before urdfdom sees it: urdfdom frees its tree
/// recursively (a link's children with it). Counted without recursion over the joints' names.
bool Reader::checkDepth(const pugi::xml_node& root) {
  std::unordered_map<std::string, std::pair<std::string, pugi::xml_node>> parent;  // child -> parent, joint
  for (pugi::xml_node j : root.children("joint"))
    parent.emplace(j.child("child").attribute("link").value(),
                   std::make_pair(std::string(j.child("parent").attribute("link").value()), j));
  std::unordered_map<std::string, int> depth;  // link -> joints above it (known so far)
  std::vector<const std::string*> path;
  for (pugi::xml_node j : root.children("joint")) {  // document order: the same joint is named every time
    auto start = parent.find(j.child("child").attribute("link").value());
    if (depth.count(start->first)) continue;
    path.clear();
    const std::string* at = &start->first;
    int base = 0;
    while (true) {
      auto known = depth.find(*at);
      if (known != depth.end()) {
        base = known->second;
        break;
      }
      auto up = parent.find(*at);
      // A root, or a loop (urdfdom refuses it; stop at the number of joints).
      if (up == parent.end() || path.size() > parent.size()) break;
      path.push_back(at);
      at = &up->second.first;
    }
    for (size_t k = path.size(); k-- > 0;) {
      const int d = base + static_cast<int>(path.size() - k);
      depth[*path[k]] = d;
      if (d > kMaxUrdfDepth) {
        const pugi::xml_node j = parent[*path[k]].second;
        error(lineOf(j), "joint '" + quoteInput(j.attribute("name").value()) + "': its child link is more than " +
                             std::to_string(kMaxUrdfDepth) +
                             " joints below the root: simbob reads URDF trees at most that deep (docs/urdf.md)");
        return false;
      }
    }
  }
  return true;
}

bool Reader::resolveFile(const std::string& name, int line, const char* what, std::string* path) {
  std::string problem;
  if (!resolveUrdfPath(name, file_, packages_, path, &problem)) {
    // A package found nowhere is said once, at its first name (WAM names it 16 times).
    const std::string package = name.substr(0, name.find('/', name.find("://") + 3));
    auto [it, first] =
        missing_.emplace(package, Missing{line, std::string(what) + " '" + quoteInput(name, 400) + "': " + problem, 0});
    ++it->second.count;
    return false;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(*path, ec)) {
    error(line,
          std::string(what) + " '" + quoteInput(name, 400) + "' not found" +
              (*path == name ? std::string() : " (looked for '" + quoteInput(*path, 400) + "')"),
          ErrorKind::MissingInput);
    return false;
  }
  if (std::find(robot_->files.begin(), robot_->files.end(), *path) == robot_->files.end())
    robot_->files.push_back(*path);
  return true;
}

bool Reader::readShape(const pugi::xml_node& x, const urdf::Geometry& g, const urdf::Pose& origin, UrdfShape* out) {
  out->line = lineOf(x);
  out->origin = toTransform(origin, x);
  if (!finite(out->origin)) {
    error(x.child("origin") ? lineOf(x.child("origin")) : out->line, "<origin> must be finite");
    return false;
  }
  pugi::xml_node shape;
  for (pugi::xml_node c : x.child("geometry").children())
    if (c.type() == pugi::node_element) {
      shape = c;
      break;
    }
  out->shape_line = shape ? lineOf(shape) : out->line;
  switch (g.type) {
    case urdf::Geometry::BOX: {
      const auto& b = static_cast<const urdf::Box&>(g);
      out->kind = UrdfShape::Box;
      out->size = {b.dim.x, b.dim.y, b.dim.z};
      break;
    }
    case urdf::Geometry::SPHERE:
      out->kind = UrdfShape::Sphere;
      out->size = {static_cast<const urdf::Sphere&>(g).radius, 0, 0};
      break;
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      out->kind = UrdfShape::Cylinder;
      out->size = {c.radius, c.length, 0};
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(g);
      out->kind = UrdfShape::Mesh;
      out->filename = m.filename;
      out->scale = {m.scale.x, m.scale.y, m.scale.z};
      return resolveFile(m.filename, out->shape_line, "mesh", &out->path);
    }
  }
  for (double s : out->size)
    if (!std::isfinite(s) || s < 0) {
      error(out->shape_line, "<" + std::string(shape.name()) + ">: sizes must be finite and >= 0");
      return false;
    }
  return true;
}

int Reader::readVisualMaterial(const pugi::xml_node& visual, const urdf::Visual& v) {
  pugi::xml_node m = visual.child("material");
  if (!m || !v.material) return -1;
  const bool inline_def = m.child("color") || m.child("texture");
  auto it = materials_.find(m.attribute("name").value());
  if (!inline_def && it != materials_.end()) return it->second;
  UrdfMaterial out;
  out.name = v.material->name;
  out.line = lineOf(m);
  out.has_color = static_cast<bool>(m.child("color")) || it != materials_.end();
  out.color = {v.material->color.r, v.material->color.g, v.material->color.b, v.material->color.a};
  out.texture = v.material->texture_filename;
  if (!out.texture.empty() &&
      !resolveFile(out.texture, lineOf(m.child("texture") ? m.child("texture") : m), "texture", &out.texture_path))
    return -2;
  robot_->materials.push_back(out);
  return static_cast<int>(robot_->materials.size()) - 1;
}

bool Reader::readLink(const pugi::xml_node& x, const urdf::Link& u) {
  UrdfLink l;
  l.name = u.name;
  l.line = lineOf(x);
  bool ok = true;
  if (u.inertial) {
    pugi::xml_node in = x.child("inertial");
    l.has_inertial = true;
    UrdfInertial& i = l.inertial;
    i.line = lineOf(in);
    i.mass_line = in.child("mass") ? lineOf(in.child("mass")) : i.line;
    i.inertia_line = in.child("inertia") ? lineOf(in.child("inertia")) : i.line;
    i.origin = toTransform(u.inertial->origin, in);
    if (!finite(i.origin)) {
      error(in.child("origin") ? lineOf(in.child("origin")) : i.line, "<origin> must be finite");
      ok = false;
    }
    i.mass = u.inertial->mass;
    const urdf::Inertial& t = *u.inertial;
    i.inertia = {t.ixx, t.ixy, t.ixz, t.ixy, t.iyy, t.iyz, t.ixz, t.iyz, t.izz};
  }
  size_t vi = 0, ci = 0;
  for (pugi::xml_node c : x.children()) {
    if (std::strcmp(c.name(), "visual") == 0 && vi < u.visual_array.size()) {
      const urdf::Visual& v = *u.visual_array[vi++];
      UrdfShape s;
      if (!v.geometry || !readShape(c, *v.geometry, v.origin, &s)) {
        ok = false;
        continue;
      }
      s.material = readVisualMaterial(c, v);
      if (s.material == -2) ok = false;
      l.visuals.push_back(s);
    } else if (std::strcmp(c.name(), "collision") == 0 && ci < u.collision_array.size()) {
      const urdf::Collision& k = *u.collision_array[ci++];
      UrdfShape s;
      if (!k.geometry || !readShape(c, *k.geometry, k.origin, &s)) {
        ok = false;
        continue;
      }
      l.collisions.push_back(s);
    }
  }
  robot_->links.push_back(std::move(l));
  return ok;
}

bool Reader::readJoint(const pugi::xml_node& x, const urdf::Joint& u, const std::map<std::string, int>& links) {
  UrdfJoint j;
  j.name = u.name;
  j.line = lineOf(x);
  switch (u.type) {
    case urdf::Joint::REVOLUTE:
      j.type = UrdfJoint::Revolute;
      break;
    case urdf::Joint::CONTINUOUS:
      j.type = UrdfJoint::Continuous;
      break;
    case urdf::Joint::PRISMATIC:
      j.type = UrdfJoint::Prismatic;
      break;
    case urdf::Joint::FLOATING:
      j.type = UrdfJoint::Floating;
      break;
    case urdf::Joint::PLANAR:
      j.type = UrdfJoint::Planar;
      break;
    case urdf::Joint::FIXED:
      j.type = UrdfJoint::Fixed;
      break;
    default:
      error(j.line, "joint '" + quoteInput(u.name) + "': unknown type");
      return false;
  }
  j.parent = links.at(u.parent_link_name);
  j.child = links.at(u.child_link_name);
  j.origin = toTransform(u.parent_to_joint_origin_transform, x);
  if (!finite(j.origin)) {
    error(x.child("origin") ? lineOf(x.child("origin")) : j.line, "<origin> must be finite");
    return false;
  }
  j.axis = {u.axis.x, u.axis.y, u.axis.z};
  const double n = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
  j.axis_line = x.child("axis") ? lineOf(x.child("axis")) : j.line;
  const bool moves = j.type == UrdfJoint::Revolute || j.type == UrdfJoint::Continuous || j.type == UrdfJoint::Prismatic;
  if (moves && !(n > 1e-9 && std::isfinite(n))) {
    error(j.axis_line, "joint '" + quoteInput(u.name) + "': <axis> must be a non-zero direction");
    return false;
  }
  if (moves && n != 1.0) j.axis = {j.axis[0] / n, j.axis[1] / n, j.axis[2] / n};
  if (u.limits) {
    j.has_limit = true;
    j.limit_line = x.child("limit") ? lineOf(x.child("limit")) : j.line;
    j.lower = u.limits->lower;
    j.upper = u.limits->upper;
    j.effort = u.limits->effort;
    j.velocity = u.limits->velocity;
  }
  if (u.dynamics) {
    j.dynamics_line = x.child("dynamics") ? lineOf(x.child("dynamics")) : j.line;
    j.damping = u.dynamics->damping;
    j.friction = u.dynamics->friction;
  }
  robot_->joints.push_back(j);
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
  if (!checkDepth(root)) return nullptr;
  std::string message;
  const UrdfModule* urdfdom = urdfModule(&message);
  if (!urdfdom) {
    error(robot_->line, message, ErrorKind::MissingInput);
    return nullptr;
  }
  urdf::ModelInterfaceSharedPtr model = urdfdom->parse(text_, &message);
  // urdfdom's links hold their children: freed from the root, a deep tree recurses once per
  // level. Unchained first, each link is freed on its own.
  struct Unchain {
    urdf::ModelInterfaceSharedPtr& model;
    ~Unchain() {
      if (!model) return;
      for (auto& named : model->links_) {
        named.second->child_links.clear();
        named.second->child_joints.clear();
      }
    }
  } unchain{model};
  if (!model) {
    error(urdfdomLine(message), "not a valid URDF: " + (message.empty() ? "urdfdom refused it" : message));
    return nullptr;
  }
  robot_->name = model->getName();
  walk(root, "robot");
  for (pugi::xml_node m : root.children("material")) {
    auto it = model->materials_.find(m.attribute("name").value());
    if (it == model->materials_.end() || materials_.count(it->first)) continue;
    UrdfMaterial out;
    out.name = it->first;
    out.line = lineOf(m);
    out.has_color = static_cast<bool>(m.child("color"));
    const urdf::Color& c = it->second->color;
    out.color = {c.r, c.g, c.b, c.a};
    out.texture = it->second->texture_filename;
    if (!out.texture.empty() && !resolveFile(out.texture, lineOf(m), "texture", &out.texture_path)) return nullptr;
    materials_[out.name] = static_cast<int>(robot_->materials.size());
    robot_->materials.push_back(out);
  }
  std::map<std::string, int> links;
  bool ok = true;
  for (pugi::xml_node x : root.children("link")) {
    urdf::LinkConstSharedPtr u = model->getLink(x.attribute("name").value());
    if (!u || links.count(u->name)) continue;
    links[u->name] = static_cast<int>(robot_->links.size());
    ok = readLink(x, *u) && ok;
  }
  std::map<std::string, int> joints;
  for (pugi::xml_node x : root.children("joint")) {
    urdf::JointConstSharedPtr u = model->getJoint(x.attribute("name").value());
    if (!u || joints.count(u->name)) continue;
    joints[u->name] = static_cast<int>(robot_->joints.size());
    ok = readJoint(x, *u, links) && ok;
    if (u->mimic) {
      UrdfJoint& j = robot_->joints.back();
      j.mimic_line = x.child("mimic") ? lineOf(x.child("mimic")) : j.line;
      j.multiplier = u->mimic->multiplier;
      j.offset = u->mimic->offset;
      mimics_.push_back({static_cast<int>(robot_->joints.size()) - 1, u->mimic->joint_name});
    }
  }
  for (const auto& [ji, leader] : mimics_) {
    auto it = joints.find(leader);
    UrdfJoint& j = robot_->joints[static_cast<size_t>(ji)];
    if (it == joints.end()) {
      error(j.mimic_line, "joint '" + quoteInput(j.name) + "': <mimic> names no joint '" + quoteInput(leader) + "'");
      ok = false;
    } else {
      j.mimic = it->second;
    }
  }
  for (pugi::xml_node g : root.children("gazebo")) ok = readGazebo(g, links, joints) && ok;
  ok = checkValues() && ok;
  if (model->getRoot()) robot_->root = links.count(model->getRoot()->name) ? links[model->getRoot()->name] : -1;
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
bool Reader::number(int line, const std::string& what, double v, bool non_negative) {
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

// Every number urdfdom read, through number(): each problem said at its element's line.
bool Reader::checkValues() {
  bool ok = true;
  // One message for an element: its first number that fails.
  auto all = [&](int line, const std::string& what, auto const& values, bool non_negative = false) {
    for (double v : values)
      if (!number(line, what, v, non_negative)) {
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
      ok = number(i.mass_line, what + ": <mass>", i.mass) && ok;
      all(i.inertia_line, what + ": <inertia>", i.inertia);
    }
    shapes(l.name, l.visuals, "visual");
    shapes(l.name, l.collisions, "collision");
  }
  for (const UrdfJoint& j : robot_->joints) {
    const std::string what = "joint '" + quoteInput(j.name) + "'";
    position(j.line, what, j.origin);
    if (j.has_limit) {
      ok = number(j.limit_line, what + ": <limit> lower", j.lower) && ok;
      ok = number(j.limit_line, what + ": <limit> upper", j.upper) && ok;
      ok = number(j.limit_line, what + ": <limit> effort", j.effort, true) && ok;
      ok = number(j.limit_line, what + ": <limit> velocity", j.velocity, true) && ok;
    }
    if (j.dynamics_line) {
      ok = number(j.dynamics_line, what + ": <dynamics> damping", j.damping, true) && ok;
      ok = number(j.dynamics_line, what + ": <dynamics> friction", j.friction, true) && ok;
    }
    if (j.mimic_line) {
      ok = number(j.mimic_line, what + ": <mimic> multiplier", j.multiplier) && ok;
      ok = number(j.mimic_line, what + ": <mimic> offset", j.offset) && ok;
    }
  }
  return ok;
}

}  // namespace

std::shared_ptr<const UrdfRobot> readUrdf(const std::string& text, const std::string& file,
                                          const UrdfPackages& packages, Diagnostics& diag) {
  Reader r(text, file, packages, diag);
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
