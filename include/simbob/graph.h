// The component graph: what a scene file says, with every parameter in its typed form and
// every Ref resolved to a component index. Knows nothing of ODE.
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <variant>
#include <vector>

#include "simbob/error.h"
#include "simbob/registry.h"
#include "simbob/values.h"

namespace simbob {

struct UrdfRobot;  // lib/urdf/urdf.h: a robot read from a URDF file

/// Text that is usually empty (a Link's Ref or Macro): one pointer, on the heap only when set,
/// so that the Link in every slot stays small. Reads as a `const std::string&`.
class RareText {
 public:
  RareText() = default;
  RareText(const std::string& s) { assign(s); }
  RareText(const char* s) { assign(s); }
  RareText(const RareText& o) { assign(o.str()); }
  RareText(RareText&& o) noexcept = default;
  RareText& operator=(const RareText& o) {
    if (this != &o) assign(o.str());
    return *this;
  }
  RareText& operator=(RareText&& o) noexcept = default;
  RareText& operator=(const std::string& s) {
    assign(s);
    return *this;
  }

  const std::string& str() const { return p_ ? *p_ : empty_(); }
  operator const std::string&() const { return str(); }
  bool empty() const { return !p_; }

  friend bool operator==(const RareText& a, const std::string& b) { return a.str() == b; }
  friend bool operator==(const RareText& a, const char* b) { return a.str() == b; }
  friend bool operator!=(const RareText& a, const std::string& b) { return a.str() != b; }
  friend std::string operator+(const RareText& a, const std::string& b) { return a.str() + b; }
  friend std::string operator+(const RareText& a, const char* b) { return a.str() + b; }
  friend std::string operator+(const std::string& a, const RareText& b) { return a + b.str(); }
  friend std::string operator+(std::string&& a, const RareText& b) { return std::move(a) + b.str(); }
  friend std::string operator+(const char* a, const RareText& b) { return a + b.str(); }

 private:
  void assign(const std::string& s) {
    if (s.empty())
      p_.reset();
    else
      p_ = std::make_unique<std::string>(s);
  }
  static const std::string& empty_() {
    static const std::string e;
    return e;
  }
  std::unique_ptr<std::string> p_;
};

/// One component-valued slot: an inline component, a Ref, or a Macro (which creates one).
struct Link {
  SourceLoc loc;
  int comp = -1;   ///< component index (inline, macro-created, or resolved Ref target)
  RareText ref;    ///< Ref text as written ("" if none)
  RareText macro;  ///< Macro name as written ("" if none)

  bool empty() const { return comp < 0 && ref.empty(); }
  bool isRef() const { return !ref.empty(); }
};

/// The value of one parameter of one component. Every parameter of every component has one,
/// so it is kept small (88 bytes; it was 144 when it held a value, a link and a list side by
/// side): a slot holds what its parameter's kind needs, file names are shared, Ref/Macro text
/// is out of line.
struct Slot {
  SourceLoc loc;
  bool set = false;  ///< written in the file (else the default applies)

  /// Value params (the default when !set). Read on a slot of another kind: an empty Value.
  const Value& value() const {
    const Value* v = std::get_if<Value>(&payload_);
    return v ? *v : emptyValue();
  }
  /// Component and Struct params. Read on a slot of another kind: an empty Link.
  const Link& link() const {
    const Link* l = std::get_if<Link>(&payload_);
    return l ? *l : emptyLink();
  }
  /// List params. Read on a slot of another kind: an empty list.
  const std::vector<Link>& list() const {
    const auto* l = std::get_if<std::vector<Link>>(&payload_);
    return l ? *l : emptyList();
  }
  /// For writing: the slot becomes one of that kind (an empty one if it held another kind).
  Value& value() { return holding<Value>(); }
  Link& link() { return holding<Link>(); }
  std::vector<Link>& list() { return holding<std::vector<Link>>(); }
  /// The link or list when the slot holds one, else nullptr (walks over every parameter).
  Link* linkIf() { return std::get_if<Link>(&payload_); }
  std::vector<Link>* listIf() { return std::get_if<std::vector<Link>>(&payload_); }

 private:
  template <class T>
  T& holding() {
    if (T* t = std::get_if<T>(&payload_)) return *t;
    return payload_.emplace<T>();
  }
  static const Value& emptyValue();
  static const Link& emptyLink();
  static const std::vector<Link>& emptyList();
  std::variant<Value, Link, std::vector<Link>> payload_;
};

/// Component indices that are usually none (an import's roots): one pointer, shared between
/// copies and on the heap only when set, so that every component stays small.
class RareIndices {
 public:
  RareIndices() = default;
  RareIndices& operator=(std::vector<int> v) {
    p_ = v.empty() ? nullptr : std::make_shared<const std::vector<int>>(std::move(v));
    return *this;
  }
  bool empty() const { return !p_; }
  size_t size() const { return p_ ? p_->size() : 0; }
  int operator[](size_t i) const { return (*p_)[i]; }
  const int* begin() const { return p_ ? p_->data() : nullptr; }
  const int* end() const { return p_ ? p_->data() + p_->size() : nullptr; }
  friend bool operator==(const RareIndices& a, const RareIndices& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }

 private:
  std::shared_ptr<const std::vector<int>> p_;
};

struct Component {
  const TypeSpec* type = nullptr;
  std::string key;       ///< Key attribute, or the parameter name it stands in
  std::string qkey;      ///< fully qualified key
  int parent = -1;       ///< owning component (-1: top level of the scene or an import root)
  bool has_key = false;  ///< Key was written in the file
  SourceLoc loc;
  std::vector<Slot> slots;  ///< parallel to type->params
  RareIndices imported;     ///< roots read from this component's File (imports)

  /// The slot of parameter `param` (generic walks: loader, writers). Lowering code reads
  /// through the typed names instead: `get(kWidth)`.
  const Slot& slot(std::string_view param) const;
  Slot& slot(std::string_view param);

  /// Typed reads by the parameter names the family files declare (see registry.h). A name the
  /// component's type does not have is a programming error: throws std::logic_error naming both.
  template <class T>
  const T& get(ValueParam<T> p) const {
    return std::get<T>(typedSlot(p).value());
  }
  uint32_t get(EnumParam p) const;
  const Link& get(LinkParam p) const { return typedSlot(p).link(); }
  const std::vector<Link>& get(ListParam p) const { return typedSlot(p).list(); }
  /// The slot behind a typed name (its source line, whether it was set).
  template <class P>
  const Slot& slotOf(P p) const {
    return typedSlot(p);
  }

 private:
  const Slot& typedSlot(const ParamName& p) const;
};

/// A whole scene: components in document order (imports appended as they are read).
struct Scene {
  std::string path;  ///< the scene file as given
  std::vector<Component> comps;
  int settings = -1;             ///< SceneSettings struct component
  std::vector<Link> cameras;     ///< CameraList
  std::vector<Link> components;  ///< ComponentList
  /// Fully qualified key -> component. Hashed: a large scene's keys share long prefixes
  /// ("Box123.Pose"), which made every insertion into a sorted map compare them 19 times over.
  /// Unordered: whoever lists the keys (a "did you mean") sorts them first.
  std::unordered_map<std::string, int> by_qkey;
  std::vector<std::string> files;  ///< every file read (scene first, then imports)
  std::set<int> load_failed;       ///< components with a load error in them (compile stays quiet on them)
  std::string content_hash;        ///< hash of all files' bytes (fnv1a64w, docs/formats.md), hex
  /// RCImportURDF component -> the robot read from its File (lib/urdf), shared by copies.
  std::map<int, std::shared_ptr<const UrdfRobot>> urdf;

  const Component& at(int i) const { return comps[static_cast<size_t>(i)]; }
  Component& at(int i) { return comps[static_cast<size_t>(i)]; }
};

enum class Format { Xml, Ini };

/// The format a scene file's name says: INI for a name ending in .ini (any case), else XML.
Format sceneFormatOf(const std::string& path);

/// Read a scene file (XML, or INI when the name ends in .ini), resolve imports and Refs, fill
/// defaults. Errors go to diag; returns false if any. With collect_all, keeps going after the
/// first error to report as many as possible (`simbob check`).
bool loadScene(const std::string& path, const Registry& reg, Scene* scene, Diagnostics& diag);

/// Same from text in memory (tests, fuzzing); `name` is used in messages and for imports.
bool loadSceneFromText(const std::string& text, const std::string& name, Format format, const Registry& reg,
                       Scene* scene, Diagnostics& diag);

/// Write the scene in `format`. With `fill_defaults`, every parameter is written, including
/// defaults and default components; otherwise only what the file set.
std::string writeScene(const Scene& scene, Format format, bool fill_defaults);

/// The global settings INI (GlobalSettings): what its keys say, as written in the file.
struct GlobalSettings {
  std::string log_file;          ///< LogFile
  std::string extension_folder;  ///< ExtensionFolder (plug-ins)
  std::string texture_folder;    ///< TextureFolder
  bool document_ini = false;     ///< DocumentIni: <scene>.ini beside a scene overrides its cameras
};
/// Reads a global settings INI file. False with the errors (file:line) in diag.
bool readGlobalSettings(const std::string& path, const Registry& reg, GlobalSettings* out, Diagnostics& diag);

/// Read an INI file of one Struct type (global settings): the global section's keys.
bool loadStructIni(const std::string& path, const Registry& reg, const std::string& struct_type, Scene* holder,
                   int* comp, Diagnostics& diag);

}  // namespace simbob
