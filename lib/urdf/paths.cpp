// package:// and relative file names of a URDF (docs/urdf.md, "Paths").
#include "urdf/paths.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <pugixml.hpp>
#include <sstream>

namespace simbob {

namespace {

namespace fs = std::filesystem;

// ROS_PACKAGE_PATH folders are searched this deep for package.xml files.
constexpr int kMaxCrawlDepth = 4;

/// The <name> of dir/package.xml, or "".
std::string packageName(const fs::path& dir) {
  std::error_code ec;
  const fs::path file = dir / "package.xml";
  if (!fs::is_regular_file(file, ec)) return "";
  pugi::xml_document doc;
  if (!doc.load_file(file.c_str())) return "";
  std::string name = doc.child("package").child_value("name");
  const size_t b = name.find_first_not_of(" \t\r\n");
  const size_t e = name.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : name.substr(b, e - b + 1);
}

bool crawl(const fs::path& dir, const std::string& name, int depth, fs::path* found) {
  if (packageName(dir) == name) {
    *found = dir;
    return true;
  }
  if (depth >= kMaxCrawlDepth) return false;
  std::error_code ec;
  std::vector<fs::path> subdirs;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string leaf = it->path().filename().string();
    if (!leaf.empty() && leaf[0] != '.' && it->is_directory(ec)) subdirs.push_back(it->path());
  }
  std::sort(subdirs.begin(), subdirs.end());  // the same package wins on every machine
  for (const fs::path& d : subdirs)
    if (crawl(d, name, depth + 1, found)) return true;
  return false;
}

bool findPackage(const std::string& name, const std::string& urdf_file, const UrdfPackages& packages, fs::path* dir) {
  std::error_code ec;
  fs::path here = fs::absolute(fs::path(urdf_file), ec).parent_path();
  for (fs::path d = here; !d.empty(); d = d.parent_path()) {
    if (packageName(d) == name) {
      *dir = d;
      return true;
    }
    if (d == d.root_path()) break;
  }
  if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream ss(env);
    std::string entry;
    while (std::getline(ss, entry, ':'))
      if (!entry.empty() && crawl(entry, name, 0, dir)) return true;
  }
  for (const auto& [n, d] : packages)
    if (n == name) {
      fs::path p(d);
      *dir = p;
      return true;
    }
  return false;
}

}  // namespace

bool resolveUrdfPath(const std::string& name, const std::string& urdf_file, const UrdfPackages& packages,
                     std::string* path, std::string* problem) {
  static const std::string kPackage = "package://", kFile = "file://";
  if (name.rfind(kPackage, 0) == 0) {
    const std::string rest = name.substr(kPackage.size());
    const size_t slash = rest.find('/');
    const std::string pkg = rest.substr(0, slash);
    fs::path dir;
    if (pkg.empty() || slash == std::string::npos) {
      *problem = "expected package://NAME/PATH";
      return false;
    }
    if (!findPackage(pkg, urdf_file, packages, &dir)) {
      *problem = "no package '" + pkg + "': no package.xml naming it in the URDF's folder or above, none in " +
                 "ROS_PACKAGE_PATH, and no --package " + pkg + "=DIR or Packages entry";
      return false;
    }
    *path = (dir / rest.substr(slash + 1)).lexically_normal().string();
    return true;
  }
  std::string n = name.rfind(kFile, 0) == 0 ? name.substr(kFile.size()) : name;
  fs::path p(n);
  if (p.is_relative()) p = fs::path(urdf_file).parent_path() / p;
  *path = p.lexically_normal().string();
  return true;
}

bool parseUrdfPackages(const std::string& text, UrdfPackages* out, std::string* problem) {
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ';')) {
    const size_t b = item.find_first_not_of(" \t");
    if (b == std::string::npos) continue;
    item = item.substr(b, item.find_last_not_of(" \t") - b + 1);
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size()) {
      *problem = "'" + item + "' is not NAME=DIR";
      return false;
    }
    out->push_back({item.substr(0, eq), item.substr(eq + 1)});
  }
  return true;
}

}  // namespace simbob

namespace simbob {

const char* urdfDriveType(uint32_t drives) {
  switch (static_cast<UrdfDrives>(drives)) {
    case UrdfDrives::None:
      return "";
    case UrdfDrives::Position:
      return "URDFPositionDrive";
    case UrdfDrives::Velocity:
      return "URDFVelocityDrive";
    case UrdfDrives::Effort:
      return "URDFEffortDrive";
  }
  return "";
}

bool urdfJointDriven(const UrdfJoint& j) {
  return (j.type == UrdfJoint::Revolute || j.type == UrdfJoint::Continuous || j.type == UrdfJoint::Prismatic) &&
         j.mimic < 0;
}

std::string urdfKey(const std::string& name) {
  std::string k = name;
  for (char& ch : k)
    if (ch == '.' || static_cast<unsigned char>(ch) < 0x20) ch = '_';
  return k;
}

}  // namespace simbob
