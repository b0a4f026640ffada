// The registry: the one list of component types, their families and parameter tables.
// The parser, the writers, `simbob types` and error messages all read it; adding a type is one
// `add` call in the file of its family (lib/components/<family>.cpp).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "simbob/name_table.h"
#include "simbob/values.h"

namespace simbob {

/// ComponentBaseTypes of the guide (chapter 2), plus Struct for plain parameter groups
/// (SceneSettings, fog settings, global settings) that have no type element or Key.
enum class Family : uint8_t {
  Body,
  GlobalSim,
  Model,
  Skin,
  Geom,
  Joint,
  Material,
  Pose,
  Motion,
  Inertia,
  Periphery,
  Controller,
  Camera,
  Struct,
};

/// "BodyComponent", "GeomComponent", ... as the guide names them.
const char* familyName(Family f);

enum class ParamKind : uint8_t {
  Value,      ///< a basic value: <Name Value="..."/>
  Component,  ///< one component: <Name><Type Key="..">..</Type></Name>, or Ref / Macro
  List,       ///< any number of components
  Struct,     ///< a group of parameters without type or key: <Name><Member Value=".."/></Name>
};

/// Range checks for numbers (applied to Number and Int values, and to every element of
/// Triple-like values when noted).
enum class Range : uint8_t {
  Any,
  Positive,     ///< > 0
  NonNegative,  ///< >= 0
  Unit,         ///< [0, 1]
};

struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::Value;
  ValueType type = ValueType::Number;  ///< Value params
  const EnumTable* table = nullptr;    ///< Enum / Bitmask params
  Value default_value;                 ///< Value params
  Range range = Range::Any;
  bool allow_infinite = false;
  std::vector<Family> families;  ///< Component / List: accepted families
  std::string default_type;      ///< Component: type created when absent ("" = stays empty)
  std::string struct_type;       ///< Struct: the Struct type describing the members
  std::string unit;              ///< "m", "kg", "deg", "s", ... ("" = none)
  std::string doc;               ///< one line for `simbob types`
};

/// Parse `text` as the value of parameter `p` as a scene file gives it (guide 4.3), with the
/// checks every parameter gets (magnitude within 1e9, the parameter's range). The error reads
/// "parameter 'Friction': expected a number, got 'abc'"; the caller puts the place and the
/// component in front. The loader and `--set` overrides both use it.
ParseResult parseParam(const ParamSpec& p, std::string_view text);

/// Typed names of parameters. A family file declares each parameter once as one of these and
/// builds both its table entry and every read from it (`c.get(kWidth)`), so a misspelled name
/// does not compile, and a read returns the type the table stores.
/// What the four kinds share: the name, and its hash in the types' name tables, computed once
/// (at compile time for the family files' constants), not at every read.
struct ParamName {
  constexpr explicit ParamName(const char* n) : name(n), size(std::string_view(n).size()), hash(NameTable::hash(n)) {}
  std::string_view view() const { return {name, size}; }
  const char* name;
  size_t size;  ///< of name, counted once (a read compares the name, not strlen's it again)
  uint64_t hash;
};
template <class T>
struct ValueParam : ParamName {
  using ParamName::ParamName;
};
/// An Enum or Bitmask parameter; reads give the value (or bits).
struct EnumParam : ParamName {
  using ParamName::ParamName;
};
/// One component (inline, Ref or Macro) or a Struct group; reads give the Link.
struct LinkParam : ParamName {
  using ParamName::ParamName;
};
/// A list of components; reads give the Links in document order.
struct ListParam : ParamName {
  using ParamName::ParamName;
};

struct PluginType;  // simbob/plugin.h

struct TypeSpec {
  TypeSpec() = default;
  TypeSpec(std::string n, Family f, int k, std::vector<ParamSpec> ps, std::vector<std::string> al, std::string d,
           bool finished = false, std::string import = "")
      : name(std::move(n)),
        family(f),
        kind(k),
        params(std::move(ps)),
        aliases(std::move(al)),
        doc(std::move(d)),
        finished_here(finished),
        import_root(std::move(import)) {}

  std::string name;  ///< "RCSphereGeom"
  Family family = Family::Struct;
  int kind = 0;                      ///< family-specific enum value used by the compile step
  std::vector<ParamSpec> params;     ///< family (inherited) parameters first, then the type's own
  std::vector<std::string> aliases;  ///< other accepted spellings ("RCMoelMatchGeom")
  std::string doc;
  bool finished_here = false;           ///< marked * (never finished) in the guide, finished in simbob
  std::string import_root;              ///< non-empty: parameter File names an XML file with this root
                                        ///< element ("Body", "Joint", "RefList") read into the scene
  std::vector<std::string> interfaces;  ///< guide interfaces it offers controllers ("RCDriver", ...)
  /// Parameters the type took once and no longer does, each with what to do instead: a file or a
  /// --set that names one is refused with that advice (README, "Changes that may affect you").
  std::vector<std::pair<std::string, std::string>> retired;
  /// The advice for a retired parameter `name`, or null.
  const std::string* retiredAdvice(std::string_view name) const {
    for (const auto& [n, advice] : retired)
      if (n == name) return &advice;
    return nullptr;
  }
  /// A plug-in's type (kept by registerPlugin), or null.
  const PluginType* plugin = nullptr;
  std::string plugin_name;  ///< the plug-in that added the type (SimbobPlugin::name), for messages

  /// Whether it offers `interface`.
  bool implements(std::string_view interface) const;

  /// Index of the parameter called `name` (exact case), or -1.
  int paramIndex(std::string_view name) const;
  /// Same for a typed name, with its hash computed before. Inline: the compile step reads
  /// every component's parameters through it, hundreds of thousands of times in a large scene.
  int paramIndex(const ParamName& p) const {
    if (indexed_ != 0 && indexed_ == params.size()) return by_name_.find(p.view(), p.hash);
    return paramIndex(p.view());
  }
  /// Same, ignoring ASCII case (INI keys are case-insensitive).
  int paramIndexIgnoreCase(std::string_view name) const;
  /// Indexes `params` by name (Registry::add does, once they are final), so that the two
  /// lookups above take constant time (the case-insensitive one log time): a plug-in type may have thousands of parameters, and reading
  /// every one of them by name must not take quadratic time.
  void indexParams();

 private:
  NameTable by_name_;                                      ///< name -> first index (indexParams)
  std::map<std::string, int, std::less<>> by_lower_name_;  ///< ASCII-lowercased name -> first index
  size_t indexed_ = 0;                                     ///< params.size() when indexed (0: not)
};

/// A Macro creates a component of a fixed type with some parameters set ("NoGeom").
struct MacroSpec {
  std::string name;
  Family family;
  std::string type;
  std::vector<std::pair<std::string, std::string>> params;  ///< name -> value text
  std::string doc;
};

/// The list of component types. A value: `main` builds one (registerBuiltins, then plug-ins)
/// and passes it down; nothing reaches a global one. Types keep their address for the
/// registry's lifetime, so components may point at them.
class Registry {
 public:
  /// Parameters every type of `family` inherits from its ComponentBaseType; call before add().
  void setFamilyParams(Family family, std::vector<ParamSpec> params);
  /// Register a type; the family's parameters are put in front of spec.params. A name or alias
  /// already taken is refused: returns false and records why in problems().
  bool add(TypeSpec spec);
  bool addMacro(MacroSpec macro);

  /// By name or alias, exact case; nullptr if unknown.
  const TypeSpec* find(std::string_view name) const;
  /// By name or alias ignoring case (INI).
  const TypeSpec* findIgnoreCase(std::string_view name) const;
  const MacroSpec* findMacro(std::string_view name) const;

  /// Registration order (stable: the order of `simbob types`).
  const std::deque<TypeSpec>& types() const { return types_; }
  const std::vector<MacroSpec>& macros() const { return macros_; }

  /// Registrations refused (duplicate names), one line each; empty when all went in.
  const std::vector<std::string>& problems() const { return problems_; }

  /// The closest registered type name within a small edit distance, or "".
  std::string suggestType(std::string_view name) const;
  /// The component types nearest to an unknown `name` for a "did you mean" (at most 3, nearest
  /// first): those within a small edit distance, else those whose name ends in the same word
  /// ("RCBoxGeom" -> the ...Geom types, nearest first: RCCuboidGeom). Struct types are left out.
  std::vector<std::string> suggestTypes(std::string_view name) const;
  /// "unknown component type 'X' (did you mean 'Y'?)"; where `plugin_family` (a place that takes
  /// controllers or peripheries, the families plug-ins add), also how to load a plug-in that would define it.
  std::string unknownTypeMessage(std::string_view name, bool plugin_family) const;

  /// Folders of URDF packages given on the command line (`--package NAME=DIR`): package://NAME/...
  /// is looked for there after a package.xml above the URDF, ROS_PACKAGE_PATH and the import's
  /// own Packages (docs/urdf.md). Not types, but the registry is what reaches every loader.
  void addPackage(std::string name, std::string dir) { packages_.emplace_back(std::move(name), std::move(dir)); }
  const std::vector<std::pair<std::string, std::string>>& packages() const { return packages_; }

 private:
  std::vector<std::pair<std::string, std::string>> packages_;
  std::deque<TypeSpec> types_;
  std::vector<MacroSpec> macros_;
  std::vector<std::string> problems_;
  std::map<Family, std::vector<ParamSpec>> family_params_;
  std::map<std::string, size_t, std::less<>> by_name_;  // names and aliases -> index, in name order
  NameTable by_name_hashed_;                            // the same, for find()
};

/// Registers every built-in family into `r` (explicit registration, no static initialisers);
/// returns false if any registration was refused (see Registry::problems()).
bool registerBuiltins(Registry& r);

// --- helpers for the parameter tables in lib/components/*.cpp: each takes the typed name ---
namespace detail {
ParamSpec valueParam(const char* name, ValueType type, Value def, std::string unit, std::string doc, Range range);
}
template <class T>
ParamSpec valueParam(ValueParam<T> name, ValueType type, const Value& def, const std::string& unit,
                     const std::string& doc, Range range = Range::Any) {
  return detail::valueParam(name.name, type, def, unit, doc, range);
}
ParamSpec enumParam(EnumParam name, ValueType type, const EnumTable* table, uint32_t def, std::string doc);
ParamSpec componentParam(LinkParam name, std::vector<Family> families, std::string default_type, std::string doc);
ParamSpec listParam(ListParam name, std::vector<Family> families, std::string doc);
ParamSpec structParam(LinkParam name, std::string struct_type, std::string doc);

}  // namespace simbob
