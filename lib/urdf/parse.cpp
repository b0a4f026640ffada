// The URDF reader's parts below the robot's structure (reader.h): numbers as urdfdom reads them,
// origins, the walk that names what simbob ignores, the <gazebo> tags Gazebo classic hands to ODE
// (UrdfGazebo), the depth of the tree and the files a robot names.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "simbob/values.h"
#include "urdf/paths.h"
#include "urdf/reader.h"

namespace simbob::urdfread {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

/// Whether a decimal text that from_chars finds out of range is below the smallest double (its
/// decimal exponent negative) rather than beyond the largest.
bool underflows(std::string_view s) {
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) s.remove_prefix(1);
  const size_t e = s.find_first_of("eE");
  long long exp = 0;
  if (e != std::string_view::npos) {
    std::string_view t = s.substr(e + 1);
    const bool neg = !t.empty() && t.front() == '-';
    if (!t.empty() && (t.front() == '+' || t.front() == '-')) t.remove_prefix(1);
    for (char c : t) exp = std::min<long long>(exp * 10 + (c - '0'), 1000000000LL);
    if (neg) exp = -exp;
    s = s.substr(0, e);
  }
  const size_t point = std::min(s.find('.'), s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (!isDigit(s[i]) || s[i] == '0') continue;
    // The first digit that is not 0 stands at 10^(point - i - 1), or 10^(point - i) after the '.'.
    const long long at = static_cast<long long>(point) - static_cast<long long>(i) - (i < point ? 1 : 0);
    return exp + at < 0;
  }
  return true;  // all zeros: from_chars gives 0 and no range error
}

}  // namespace

std::optional<double> urdfNumber(std::string_view text) {
  if (std::optional<double> v = parseNumber(text)) return v;
  // parseNumber refuses a magnitude below the smallest double; urdfdom's stream reads it as 0.
  std::string_view s = text;
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  std::string_view digits = s;
  if (!digits.empty() && (digits.front() == '+' || digits.front() == '-')) digits.remove_prefix(1);
  if (digits.empty() || !(isDigit(digits.front()) || digits.front() == '.')) return std::nullopt;
  double d = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), d, std::chars_format::general);
  if (ec != std::errc::result_out_of_range || ptr != digits.data() + digits.size() || !underflows(s))
    return std::nullopt;
  return s.front() == '-' ? -0.0 : 0.0;
}

int Reader::lineOf(const pugi::xml_node& n) const {
  const auto off = static_cast<size_t>(std::max<ptrdiff_t>(0, n.offset_debug()));
  return static_cast<int>(std::upper_bound(newlines_.begin(), newlines_.end(), off) - newlines_.begin()) + 1;
}

void Reader::ignore(int line, const std::string& what) {
  // A map, not a search of the notes: a file may hold 200,000 different unknown elements.
  auto [it, added] = ignored_index_.emplace(what, robot_->ignored.size());
  if (!added) {
    ++robot_->ignored[it->second].count;
    return;
  }
  robot_->ignored.push_back({line, what, 1});
}

// --- values: urdfdom's rules, simbob's messages --------------------------------------------------

bool Reader::required(const pugi::xml_node& el, const char* attr, const std::string& what) {
  if (el.attribute(attr)) return true;
  error(lineOf(el), what + ": <" + std::string(el.name()) + "> needs " + attr + "=\"...\"");
  return false;
}

bool Reader::numberIf(const pugi::xml_node& el, const char* attr, const std::string& what, double* out) {
  if (!el.attribute(attr)) return true;
  const std::optional<double> v = number(el, attr, what);
  if (v) *out = *v;
  return v.has_value();
}

std::optional<double> Reader::number(const pugi::xml_node& el, const char* attr, const std::string& what) {
  const char* text = el.attribute(attr).value();
  std::optional<double> v = urdfNumber(text);
  if (!v)
    error(lineOf(el),
          what + ": <" + std::string(el.name()) + " " + attr + "=\"" + quoteInput(text, 80) + "\">: not a number");
  return v;
}

bool Reader::numbers(const pugi::xml_node& el, const char* attr, const std::string& what, size_t n, double* out) {
  // urdfdom splits at blanks (pugixml has made every tab and line break of an attribute one)
  // and reads each piece as a number; it needs exactly n of them.
  const std::string_view text = el.attribute(attr).value();
  auto say = [&](const std::string& problem) {
    error(lineOf(el),
          what + ": <" + std::string(el.name()) + " " + attr + "=\"" + quoteInput(text, 80) + "\">: " + problem);
    return false;
  };
  size_t count = 0;
  for (size_t i = 0; i < text.size();) {
    if (std::strchr(" \t\r\n", text[i])) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < text.size() && !std::strchr(" \t\r\n", text[j])) ++j;
    const std::string_view piece = text.substr(i, j - i);
    const std::optional<double> v = urdfNumber(piece);
    if (!v) return say("'" + quoteInput(piece, 40) + "' is not a number");
    if (count < n) out[count] = *v;
    ++count;
    i = j;
  }
  if (count != n) return say(std::to_string(n) + " numbers expected, found " + std::to_string(count));
  return true;
}

bool Reader::origin(const pugi::xml_node& el, const std::string& what, Transform* out) {
  *out = Transform{};
  const pugi::xml_node o = el.child("origin");
  if (!o) return true;
  if (o.attribute("xyz") && !numbers(o, "xyz", what, 3, out->p.data())) return false;
  if (o.attribute("rpy")) {
    double rpy[3];
    if (!numbers(o, "rpy", what, 3, rpy)) return false;
    out->q = quatFromRpy(rpy[0], rpy[1], rpy[2]);
  }
  return true;
}

namespace {

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

}  // namespace

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

// --- <gazebo>: what Gazebo classic's URDF converter (sdformat's parser_urdf.cc) hands to ODE -----

namespace {

/// A tag's text as Gazebo reads it: its `value` attribute, or else its text, without blanks around.
std::string gazeboText(const pugi::xml_node& tag) {
  std::string t = tag.attribute("value") ? tag.attribute("value").value() : tag.child_value();
  const size_t b = t.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return t.substr(b, t.find_last_not_of(" \t\r\n") - b + 1);
}

}  // namespace

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
  if (!range(line, what + ": <" + tag.name() + ">", *v)) return false;
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

/// Refuses a tree deeper than kMaxUrdfDepth before anything else is read (docs/urdf.md,
/// "Limits"). Counted without recursion over the joints' names.
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
      // A root, or a loop (checkTree refuses it; stop at the number of joints).
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

}  // namespace simbob::urdfread
