// The URDF reader's state, shared by read.cpp (robot, materials, links, joints, the tree, the
// values' checks) and parse.cpp (numbers, origins, the walk for what is ignored, <gazebo>,
// file names). One pugixml tree per file: every value and every line come from it.
#pragma once

#include <pugixml.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "urdf/urdf.h"

namespace simbob::urdfread {

/// A material's values as urdfdom's rules give them: rgba (float-rounded, black without one)
/// and a texture file name.
struct MaterialValues {
  Rgba color{0, 0, 0, 1};
  std::string texture;
  bool has_rgba = false;
  bool has_texture = false;  ///< a <texture filename>
};

class Reader {
 public:
  Reader(const std::string& text, const std::string& file, const UrdfPackages& packages, Diagnostics& diag);

  std::shared_ptr<const UrdfRobot> read();

 private:
  // --- parse.cpp -----------------------------------------------------------------------------
  int lineOf(const pugi::xml_node& n) const;
  void error(int line, const std::string& msg, ErrorKind kind = ErrorKind::InvalidInput) {
    diag_.error({file_, line}, msg, kind);
  }
  void ignore(int line, const std::string& what);
  void walk(const pugi::xml_node& n, const std::string& path);
  /// The number in attribute `attr` of `el` (which must have it): an error at el's line if it
  /// is not one.
  std::optional<double> number(const pugi::xml_node& el, const char* attr, const std::string& what);
  /// `n` numbers in attribute `attr` of `el`, separated by blanks.
  bool numbers(const pugi::xml_node& el, const char* attr, const std::string& what, size_t n, double* out);
  /// An attribute that must be there: an error at el's line naming it if it is not.
  bool required(const pugi::xml_node& el, const char* attr, const std::string& what);
  /// A number attribute that may be missing: *out keeps its default then.
  bool numberIf(const pugi::xml_node& el, const char* attr, const std::string& what, double* out);
  /// The first <origin> child of `el` (identity without one): xyz and rpy, each optional.
  bool origin(const pugi::xml_node& el, const std::string& what, Transform* out);
  bool checkDepth(const pugi::xml_node& root);
  bool resolveFile(const std::string& name, int line, const char* what, std::string* path);
  bool readGazebo(const pugi::xml_node& g, const std::map<std::string, int>& links,
                  const std::map<std::string, int>& joints);
  bool gazeboNumber(const pugi::xml_node& tag, const std::string& what, double lo, bool lo_open, UrdfTag* out);
  bool gazeboBool(const pugi::xml_node& tag, const std::string& what, bool invert, UrdfTag* out);

  // --- read.cpp ------------------------------------------------------------------------------
  bool readRobot(const pugi::xml_node& root);
  bool parseMaterial(const pugi::xml_node& m, const std::string& what, MaterialValues* out);
  bool readMaterials(const pugi::xml_node& root);
  bool readInertial(const pugi::xml_node& in, const std::string& what, UrdfInertial* i);
  bool readShape(const pugi::xml_node& x, const std::string& what, UrdfShape* out);
  int readVisualMaterial(const pugi::xml_node& visual, const std::string& what, bool* ok);
  bool readLink(const pugi::xml_node& x);
  std::shared_ptr<const UrdfRobot> finish(bool ok);
  bool readJointType(const pugi::xml_node& x, const std::string& what, UrdfJoint* j);
  bool readJointParts(const pugi::xml_node& x, const std::string& what, UrdfJoint* j, std::string* leader);
  bool readJointLink(const pugi::xml_node& x, const char* which, const std::string& what, int* out);
  bool readJoint(const pugi::xml_node& x);
  bool checkTree();
  bool range(int line, const std::string& what, double v, bool non_negative = false);
  bool mimicsAcyclic();
  bool checkValues();

  const std::string& text_;
  std::string file_;
  const UrdfPackages& packages_;
  Diagnostics& diag_;
  std::vector<size_t> newlines_;
  pugi::xml_document doc_;
  std::shared_ptr<UrdfRobot> robot_ = std::make_shared<UrdfRobot>();
  std::map<std::string, int> materials_;                   // robot-level material name -> index
  std::map<std::string, MaterialValues> material_values_;  // urdfdom's material map: robot-level, then inline
  std::map<std::string, int> links_;                       // link name -> UrdfRobot::links index
  std::map<std::string, int> joints_;                      // joint name -> UrdfRobot::joints index
  std::unordered_map<std::string, size_t> ignored_index_;  // note text -> UrdfRobot::ignored index
  std::vector<std::pair<int, std::string>> mimics_;        // joint index, the joint it follows
  struct Missing {
    int line;
    std::string message;
    int count;
  };
  std::map<std::string, Missing> missing_;  // package:// prefix -> its first name
};

/// A number as urdfdom reads one (a C-locale stream, the whole text): a sign, digits with at
/// most one '.', an exponent; blanks around it; no "inf", "nan" or hexadecimal. Correctly
/// rounded, so the very double urdfdom's stream gives, and 0 for a magnitude below the smallest
/// double as the stream gives. std::nullopt for anything else.
std::optional<double> urdfNumber(std::string_view text);

}  // namespace simbob::urdfread
