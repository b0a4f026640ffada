#include "simbob/registry.h"

#include <algorithm>
#include <cctype>

#include "simbob/error.h"

namespace simbob {

const char* familyName(Family f) {
  switch (f) {
    case Family::Body:
      return "BodyComponent";
    case Family::GlobalSim:
      return "GlobalSimComponent";
    case Family::Model:
      return "ModelComponent";
    case Family::Skin:
      return "SkinComponent";
    case Family::Geom:
      return "GeomComponent";
    case Family::Joint:
      return "JointComponent";
    case Family::Material:
      return "MaterialComponent";
    case Family::Pose:
      return "PoseComponent";
    case Family::Motion:
      return "MotionComponent";
    case Family::Inertia:
      return "InertiaComponent";
    case Family::Periphery:
      return "PeripheryComponent";
    case Family::Controller:
      return "ControllerComponent";
    case Family::Camera:
      return "CameraComponent";
    case Family::Struct:
      return "Struct";
  }
  return "?";
}

namespace {

std::string lowerAscii(std::string_view s) {
  std::string out(s);
  for (char& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

}  // namespace

void TypeSpec::indexParams() {
  by_name_.clear();
  by_lower_name_.clear();
  for (size_t i = 0; i < params.size(); ++i) {
    by_name_.add(params[i].name, static_cast<int>(i));  // keeps the first of equal names
    by_lower_name_.emplace(lowerAscii(params[i].name), static_cast<int>(i));
  }
  indexed_ = params.size();
}

int TypeSpec::paramIndex(std::string_view n) const {
  if (indexed_ != 0 && indexed_ == params.size()) {
    return by_name_.find(n);
  }
  for (size_t i = 0; i < params.size(); ++i)
    if (params[i].name == n) return static_cast<int>(i);
  return -1;
}

int TypeSpec::paramIndexIgnoreCase(std::string_view n) const {
  if (indexed_ != 0 && indexed_ == params.size()) {
    auto it = by_lower_name_.find(lowerAscii(n));
    return it == by_lower_name_.end() ? -1 : it->second;
  }
  for (size_t i = 0; i < params.size(); ++i)
    if (equalsIgnoreCase(params[i].name, n)) return static_cast<int>(i);
  return -1;
}

void Registry::setFamilyParams(Family family, std::vector<ParamSpec> params) {
  family_params_[family] = std::move(params);
}

bool TypeSpec::implements(std::string_view interface) const {
  for (const auto& i : interfaces)
    if (i == interface) return true;
  return false;
}

bool Registry::add(TypeSpec spec) {
  std::vector<std::string> names{spec.name};
  names.insert(names.end(), spec.aliases.begin(), spec.aliases.end());
  for (const auto& n : names) {
    if (n.empty() || findIgnoreCase(n) || findMacro(n)) {
      problems_.push_back("component type '" + spec.name + "': the name '" + n +
                          (n.empty() ? "' is empty" : "' is already registered"));
      return false;
    }
  }
  auto it = family_params_.find(spec.family);
  if (it != family_params_.end()) spec.params.insert(spec.params.begin(), it->second.begin(), it->second.end());
  spec.indexParams();
  size_t index = types_.size();
  for (const auto& n : names) {
    by_name_[n] = index;
    by_name_hashed_.add(n, static_cast<int>(index));
  }
  types_.push_back(std::move(spec));
  return true;
}

bool Registry::addMacro(MacroSpec macro) {
  if (findMacro(macro.name) || findIgnoreCase(macro.name)) {
    problems_.push_back("macro '" + macro.name + "': the name is already registered");
    return false;
  }
  macros_.push_back(std::move(macro));
  return true;
}

const TypeSpec* Registry::find(std::string_view name) const {
  const int index = by_name_hashed_.find(name);
  return index < 0 ? nullptr : &types_[static_cast<size_t>(index)];
}

const TypeSpec* Registry::findIgnoreCase(std::string_view name) const {
  if (const TypeSpec* t = find(name)) return t;
  for (const auto& [n, index] : by_name_)
    if (equalsIgnoreCase(n, name)) return &types_[index];
  return nullptr;
}

const MacroSpec* Registry::findMacro(std::string_view name) const {
  for (const auto& m : macros_)
    if (equalsIgnoreCase(m.name, name)) return &m;
  return nullptr;
}

std::string Registry::suggestType(std::string_view name) const {
  std::vector<std::string> names;
  for (const auto& [n, index] : by_name_) names.push_back(n);
  return didYouMean(name, names);
}

std::vector<std::string> Registry::suggestTypes(std::string_view name) const {
  std::vector<std::pair<size_t, const std::string*>> near;
  // Distance 0 is a name in another case (<RCsky/>): the first suggestion.
  auto consider = [&](const std::string& n, size_t d) { near.emplace_back(d, &n); };
  const size_t limit = std::max<size_t>(2, name.size() / 3);
  for (const auto& [n, index] : by_name_) {
    if (types_[index].family == Family::Struct) continue;
    const size_t d = editDistance(name, n);
    if (d <= limit && d < n.size()) consider(types_[index].name, d);  // an alias suggests its type
  }
  if (near.empty()) {
    // No close spelling: the last capitalised word ("Geom" of "RCBoxGeom") names the family the
    // writer had in mind; offer its nearest members.
    size_t start = name.size();
    while (start > 0 && !std::isupper(static_cast<unsigned char>(name[start - 1]))) --start;
    if (start > 0) --start;
    const std::string_view word = name.substr(start);
    if (word.size() >= 3 && word.size() < name.size())
      for (const TypeSpec& t : types_) {
        if (t.family == Family::Struct || t.name.size() <= word.size() ||
            !equalsIgnoreCase(std::string_view(t.name).substr(t.name.size() - word.size()), word))
          continue;
        consider(t.name, editDistance(name, t.name));
      }
  }
  std::stable_sort(near.begin(), near.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : *a.second < *b.second;
  });
  std::vector<std::string> out;
  for (const auto& [d, n] : near) {
    // Only the nearest: a list of equally near names, never a far one after a near one.
    if (out.size() == 3 || d > near.front().first) break;
    if (std::find(out.begin(), out.end(), *n) == out.end()) out.push_back(*n);
  }
  return out;
}

std::string Registry::unknownTypeMessage(std::string_view name, bool plugin_family) const {
  std::string msg = "unknown component type '" + quoteInput(name) + "'";
  const std::vector<std::string> near = suggestTypes(name);
  if (!near.empty()) {
    msg += " (did you mean ";
    for (size_t i = 0; i < near.size(); ++i)
      msg += (i == 0 ? "" : i + 1 == near.size() ? " or " : ", ") + ("'" + near[i] + "'");
    msg += "?)";
  }
  if (plugin_family) msg += "; if a plug-in defines it, load the plug-in with --plugin FILE";
  return msg;
}

ParamSpec detail::valueParam(const char* name, ValueType type, Value def, std::string unit, std::string doc,
                             Range range) {
  ParamSpec p;
  p.name = name;
  p.kind = ParamKind::Value;
  p.type = type;
  p.default_value = std::move(def);
  p.unit = std::move(unit);
  p.doc = std::move(doc);
  p.range = range;
  return p;
}

ParamSpec enumParam(EnumParam name, ValueType type, const EnumTable* table, uint32_t def, std::string doc) {
  ParamSpec p;
  p.name = name.name;
  p.kind = ParamKind::Value;
  p.type = type;
  p.table = table;
  if (type == ValueType::Bitmask)
    p.default_value = BitmaskValue{def};
  else
    p.default_value = EnumValue{def};
  p.doc = std::move(doc);
  return p;
}

ParamSpec componentParam(LinkParam name, std::vector<Family> families, std::string default_type, std::string doc) {
  ParamSpec p;
  p.name = name.name;
  p.kind = ParamKind::Component;
  p.families = std::move(families);
  p.default_type = std::move(default_type);
  p.doc = std::move(doc);
  return p;
}

ParamSpec listParam(ListParam name, std::vector<Family> families, std::string doc) {
  ParamSpec p;
  p.name = name.name;
  p.kind = ParamKind::List;
  p.families = std::move(families);
  p.doc = std::move(doc);
  return p;
}

ParamSpec structParam(LinkParam name, std::string struct_type, std::string doc) {
  ParamSpec p;
  p.name = name.name;
  p.kind = ParamKind::Struct;
  p.struct_type = std::move(struct_type);
  p.default_type = p.struct_type;
  p.doc = std::move(doc);
  return p;
}

}  // namespace simbob
