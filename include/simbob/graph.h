// The component graph: what a scene file says, with every parameter in its typed form and
// every Ref resolved to a component index. Knows nothing of ODE.
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <new>
#include <set>
#include <string>
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
/// so it is kept small (80 bytes; it was 144 when it held a value, a link and a list side by
/// side): a slot holds what its parameter's kind needs, in one union whose tag shares a word
/// with `set`; file names are shared, Ref/Macro text is out of line.
struct Slot {
  SourceLoc loc;
  bool set = false;  ///< written in the file (else the default applies)

  Slot() { new (&value_) Value(); }
  Slot(const Slot& o) : loc(o.loc), set(o.set) { construct(o); }
  Slot(Slot&& o) noexcept : loc(o.loc), set(o.set) { construct(std::move(o)); }
  Slot& operator=(const Slot& o) {
    if (this != &o) {
      Slot copy(o);
      *this = std::move(copy);
    }
    return *this;
  }
  Slot& operator=(Slot&& o) noexcept {
    if (this != &o) {
      destroy();
      loc = o.loc;
      set = o.set;
      construct(std::move(o));
    }
    return *this;
  }
  ~Slot() { destroy(); }

  /// Value params (the default when !set). Read on a slot of another kind: an empty Value.
  const Value& value() const { return kind_ == Kind::Value ? value_ : emptyValue(); }
  /// Component and Struct params. Read on a slot of another kind: an empty Link.
  const Link& link() const { return kind_ == Kind::Link ? link_ : emptyLink(); }
  /// List params. Read on a slot of another kind: an empty list.
  const std::vector<Link>& list() const { return kind_ == Kind::List ? list_ : emptyList(); }
  /// For writing: the slot becomes one of that kind (an empty one if it held another kind).
  Value& value() {
    if (kind_ != Kind::Value) become(Kind::Value);
    return value_;
  }
  Link& link() {
    if (kind_ != Kind::Link) become(Kind::Link);
    return link_;
  }
  std::vector<Link>& list() {
    if (kind_ != Kind::List) become(Kind::List);
    return list_;
  }
  /// The link or list when the slot holds one, else nullptr (walks over every parameter).
  Link* linkIf() { return kind_ == Kind::Link ? &link_ : nullptr; }
  std::vector<Link>* listIf() { return kind_ == Kind::List ? &list_ : nullptr; }

 private:
  enum class Kind : uint8_t { Value, Link, List };
  void destroy() {
    switch (kind_) {
      case Kind::Value:
        value_.~Value();
        break;
      case Kind::Link:
        link_.~Link();
        break;
      case Kind::List:
        list_.~vector();
        break;
    }
  }
  void become(Kind k) {
    destroy();
    kind_ = k;
    switch (k) {
      case Kind::Value:
        new (&value_) Value();
        break;
      case Kind::Link:
        new (&link_) Link();
        break;
      case Kind::List:
        new (&list_) std::vector<Link>();
        break;
    }
  }
  template <class S>
  void construct(S&& o) {  // this holds nothing yet
    kind_ = o.kind_;
    switch (kind_) {
      case Kind::Value:
        new (&value_) Value(std::forward<S>(o).value_);
        break;
      case Kind::Link:
        new (&link_) Link(std::forward<S>(o).link_);
        break;
      case Kind::List:
        new (&list_) std::vector<Link>(std::forward<S>(o).list_);
        break;
    }
  }
  static const Value& emptyValue();
  static const Link& emptyLink();
  static const std::vector<Link>& emptyList();
  Kind kind_ = Kind::Value;
  union {
    Value value_;
    Link link_;
    std::vector<Link> list_;
  };
};

/// Component indices that are usually none (an import's roots): one pointer, on the heap only
/// when set, so that every component stays small.
class RareIndices {
 public:
  RareIndices() = default;
  RareIndices(const RareIndices& o) : p_(o.p_ ? std::make_unique<std::vector<int>>(*o.p_) : nullptr) {}
  RareIndices(RareIndices&& o) noexcept = default;
  RareIndices& operator=(const RareIndices& o) {
    if (this != &o) p_ = o.p_ ? std::make_unique<std::vector<int>>(*o.p_) : nullptr;
    return *this;
  }
  RareIndices& operator=(RareIndices&& o) noexcept = default;
  ~RareIndices() = default;
  RareIndices& operator=(std::vector<int> v) {
    p_ = v.empty() ? nullptr : std::make_unique<std::vector<int>>(std::move(v));
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
  std::unique_ptr<std::vector<int>> p_;
};

/// One component of the graph: 96 bytes and its slots, so that a 20,000-body scene's 100,000
/// components stay small beside the file they come from.
struct Component {
  const TypeSpec* type = nullptr;
  std::string qkey;      ///< fully qualified key
  int parent = -1;       ///< owning component (-1: top level of the scene or an import root)
  uint32_t key_at : 31;  ///< where key() starts in qkey
  bool has_key : 1;      ///< Key was written in the file
  SourceLoc loc;
  std::vector<Slot> slots;  ///< parallel to type->params
  RareIndices imported;     ///< roots read from this component's File (imports)

  Component() : key_at(0), has_key(false) {}
  /// The Key attribute, or the parameter name it stands in: the last part of qkey (not stored
  /// twice). Empty for a component that takes its parent's key.
  std::string key() const { return qkey.substr(key_at); }
  /// qkey becomes `parent_qkey`.`key` (either alone when the other is empty), key() `key`.
  void setKey(const std::string& parent_qkey, const std::string& key) {
    qkey = parent_qkey.empty() ? key : (key.empty() ? parent_qkey : parent_qkey + "." + key);
    key_at = static_cast<uint32_t>(qkey.size() - key.size());
  }

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
  const Slot& typedSlot(const ParamName& p) const {
    const int i = type->paramIndex(p);
    if (i < 0) missingParam(p);
    return slots[static_cast<size_t>(i)];
  }
  [[noreturn]] void missingParam(const ParamName& p) const;
};

/// Fully qualified key -> component: an open-addressing table of component indices, hashed by
/// the components' own qkey strings, so that the keys are not stored twice. A large scene's
/// map of strings took 45 bytes and an allocation per component; this takes 8 bytes at most.
/// A key's component must keep its qkey while it is in the table.
class KeyIndex {
 public:
  /// The component keyed `qkey`, or -1.
  int find(std::string_view qkey, const std::vector<Component>& comps) const;
  /// Adds comps[index] by its qkey. Returns -1, or the component that has that key already (and
  /// then adds nothing).
  int insert(int index, const std::vector<Component>& comps);
  size_t size() const { return size_; }
  /// Room for `n` keys without growing (a large list reserves for the rest of its items).
  void reserve(size_t n, const std::vector<Component>& comps);
  /// The components in the table, in no particular order.
  std::vector<int> indices() const;

 private:
  void rehash(size_t slots, const std::vector<Component>& comps);
  std::vector<int32_t> slots_;  ///< component index + 1, 0 empty; size a power of two, at most half full
  size_t size_ = 0;
};

/// A whole scene: components in document order (imports appended as they are read).
struct Scene {
  std::string path;        ///< the scene file as given
  bool bare_urdf = false;  ///< made around a bare .urdf file (`simbob run robot.urdf`)
  std::vector<Component> comps;
  int settings = -1;             ///< SceneSettings struct component
  std::vector<Link> cameras;     ///< CameraList
  std::vector<Link> components;  ///< ComponentList
  /// Fully qualified key -> component (see KeyIndex); use find(), addKey(), sortedKeys().
  KeyIndex by_qkey;
  std::vector<std::string> files;  ///< every file read (scene first, then imports)
  std::set<int> load_failed;       ///< components with a load error in them (compile stays quiet on them)
  std::string content_hash;        ///< hash of all files' bytes (fnv1a64w, docs/formats.md), hex
  /// RCImportURDF component -> the robot read from its File (lib/urdf), shared by copies.
  std::map<int, std::shared_ptr<const UrdfRobot>> urdf;

  const Component& at(int i) const { return comps[static_cast<size_t>(i)]; }
  Component& at(int i) { return comps[static_cast<size_t>(i)]; }
  /// The component with fully qualified key `qkey`, or -1.
  int find(std::string_view qkey) const { return by_qkey.find(qkey, comps); }
  /// Makes component `i` findable by its qkey; returns -1, or the component that has the key.
  int addKey(int i) { return by_qkey.insert(i, comps); }
  /// Every key, sorted (for "did you mean": of equally near keys the first in key order).
  std::vector<std::string> sortedKeys() const;
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
