// Builds the component graph from a Source, driven only by the registry's parameter tables:
// no type-specific code here. Then reads imports, resolves Refs and checks for cycles.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include <pugixml.hpp>

#include "scene/source.h"
#include "simbob/tool/files.h"
#include "simbob/graph.h"
#include "urdf/urdf.h"

namespace simbob {

namespace {

constexpr int kMaxImportDepth = 16;
constexpr int kMaxNesting = 200;
// Files importing the next one twice double the graph with every file: bound what the imports
// and the whole graph may expand to (a few KB of memory per component).
constexpr int kMaxImports = 5000;
constexpr size_t kMaxComponents = 300000;

// The content hash: FNV-1a's step over 64-bit little-endian words instead of bytes ("fnv1a64w"
// in summaries), the tail byte by byte. Byte-wise FNV-1a cost 8 instructions per byte of a large
// scene, more than pugixml's parse of it; each step is a bijection of the running hash, so any
// changed word changes the result.
uint64_t fnv1aWords(uint64_t h, const std::string& bytes) {
  constexpr uint64_t kPrime = 1099511628211ull;
  const char* p = bytes.data();
  size_t n = bytes.size();
  for (; n >= 8; p += 8, n -= 8) {
    uint64_t w;
    std::memcpy(&w, p, sizeof w);  // one load (GCC does not fold a loop of byte shifts into one)
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    w = __builtin_bswap64(w);  // little-endian words on every host: the same hash everywhere
#endif
    h = (h ^ w) * kPrime;
    h ^= h >> 32;  // the high bytes of a word reach the low bits of the hash
  }
  for (; n > 0; ++p, --n) h = (h ^ static_cast<unsigned char>(*p)) * kPrime;
  return h;
}

// A scene file's text read again, for a message that needs it as it was; empty if it cannot be.
std::string reread(const std::string& path) {
  std::string text, err;
  return readFile(path, kMaxSceneFileBytes, &text, &err, true) ? text : std::string();
}

std::string hex64(uint64_t v) {
  static const char* digits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4) s[static_cast<size_t>(i)] = digits[v & 15];
  return s;
}

bool familyAccepted(const ParamSpec& p, Family f) {
  return std::find(p.families.begin(), p.families.end(), f) != p.families.end();
}

std::string familiesText(const ParamSpec& p) {
  std::string s;
  for (size_t i = 0; i < p.families.size(); ++i) {
    if (i) s += i + 1 == p.families.size() ? " or " : ", ";
    s += familyName(p.families[i]);
  }
  return s;
}

// What a message is about: "RCSphereGeom 'Ball.Geom'", or a fixed text such as "<RefList>",
// or nothing for the scene root. Made into text only when a message needs it: building the
// text for every component cost more than a bare parse's time per element.
class What {
 public:
  explicit What(std::string fixed) : fixed_(std::move(fixed)) {}
  /// `qkey` must outlive this.
  What(const TypeSpec* type, const std::string* qkey) : type_(type), qkey_(qkey) {}
  std::string str() const {
    if (!type_) return fixed_;
    return type_->name + (qkey_->empty() ? std::string() : " '" + *qkey_ + "'");
  }

 private:
  std::string fixed_;
  const TypeSpec* type_ = nullptr;
  const std::string* qkey_ = nullptr;
};

// "RCSphereGeom 'Ball.Geom': " before a message; nothing for the scene root.
std::string prefix(const What& about) {
  const std::string what = about.str();
  return what.empty() ? std::string() : what + ": ";
}

class Builder {
 public:
  Builder(const Registry& reg, Scene& scene, Diagnostics& diag) : reg_(reg), scene_(scene), diag_(diag) {}

  // Build one component of type t from src; returns its index. `loc` is taken by value on
  // purpose: callers pass slots of components that building more components moves.
  int build(const TypeSpec* t, Source* src, const std::string& key, bool has_key, int parent,
            const std::string& parent_qkey,
            SourceLoc loc,  // NOLINT(performance-unnecessary-value-param)
            bool register_key = true) {
    if (too_big_) return -1;
    if (scene_.comps.size() >= kMaxComponents) {
      too_big_ = true;
      diag_.error(loc, "the scene expands to more than " + std::to_string(kMaxComponents) +
                           " components (imports or lists that multiply?)");
      return -1;
    }
    if (++depth_ > kMaxNesting) {
      --depth_;
      // Every parameter at the limit would say it again: once per scene is enough.
      if (!nesting_reported_)
        diag_.error(loc, "components nested deeper than " + std::to_string(kMaxNesting) + " levels");
      nesting_reported_ = true;
      return -1;
    }
    int index = static_cast<int>(scene_.comps.size());
    const size_t errors_before = diag_.errors().size();
    {
      Component c;
      c.type = t;
      c.setKey(parent_qkey, key);
      c.has_key = has_key;
      c.parent = parent;
      c.loc = loc;
      c.slots.resize(t->params.size());
      scene_.comps.push_back(std::move(c));
    }
    if (register_key && t->family != Family::Struct) registerKey(index);
    const std::string qkey = scene_.at(index).qkey;
    // The root <Simulation> needs no name in messages: the file:line says where.
    const What what =
        parent < 0 && t->family == Family::Struct && t->name == "Simulation" ? What(std::string()) : What(t, &qkey);

    for (size_t pi = 0; pi < t->params.size(); ++pi) {
      const ParamSpec& p = t->params[pi];
      if (p.kind == ParamKind::Value) {
        // Values build no components (which could move this one): written in place, the
        // default copied only when the file does not give a good value.
        Slot& slot = scene_.at(index).slots[pi];
        slot.loc = loc;
        SourceValue v = src ? src->value(p.name) : SourceValue{};
        if (v.present) {
          slot.loc = {loc.file, v.line};
          if (!v.error.empty())
            diag_.error(slot.loc, prefix(what) + v.error);
          else
            slot.set = parseInto(p, v.text, &slot.value(), slot.loc, what);
        }
        if (!slot.set) slot.value() = p.default_value;
        continue;
      }
      Slot slot;
      slot.loc = loc;
      switch (p.kind) {
        case ParamKind::Value:  // filled in place above
          break;
        case ParamKind::Component: {
          SourceLink l = src ? src->component(p.name) : SourceLink{};
          if (l.present) {
            slot.set = true;
            slot.loc = {loc.file, l.line};
            slot.link() = makeLink(l, p, p.name, index, qkey, loc.file, what);
          } else if (!p.default_type.empty()) {
            slot.link().comp = sharedDefault(p.default_type);
          }
          break;
        }
        case ParamKind::Struct: {
          int line = loc.line;
          std::unique_ptr<Source> s = src ? src->structure(p.name, &line) : nullptr;
          const TypeSpec* st = reg_.find(p.struct_type);
          slot.loc = {loc.file, line};
          slot.link().comp = build(st, s.get(), p.name, false, index, qkey, slot.loc);
          // An empty <SceneSettings/> sets nothing (and INI cannot even write it): set only
          // when a member is.
          if (s && slot.link().comp >= 0)
            for (const Slot& member : scene_.at(slot.link().comp).slots) slot.set = slot.set || member.set;
          break;
        }
        case ParamKind::List: {
          bool present = false;
          int line = loc.line;
          std::vector<SourceLink> items = src ? src->list(p.name, &present, &line) : std::vector<SourceLink>{};
          slot.set = present;
          slot.loc = {loc.file, line};
          std::vector<Link>& list = slot.list();
          list.reserve(items.size());
          const size_t comps_before = scene_.comps.size();
          for (size_t i = 0; i < items.size(); ++i) {
            if (i == kEstimateAfter) reserveComponents(comps_before, i, items.size());
            const std::string default_key(items[i].type);
            list.push_back(makeLink(items[i], p, default_key, index, qkey, loc.file, what));
            items[i].body.reset();
            src->forget(items[i]);
          }
          break;
        }
      }
      scene_.at(index).slots[pi] = std::move(slot);
    }

    if (src) reportUnread(*t, *src, loc, what);
    if (!t->import_root.empty()) readImport(index, loc);
    if (diag_.errors().size() > errors_before) scene_.load_failed.insert(index);
    --depth_;
    return index;
  }

  /// Every parameter the source gave that type `t` does not take (or took twice), with a "did
  /// you mean" or the list of what it takes.
  void reportUnread(const TypeSpec& t, const Source& src, const SourceLoc& loc, const What& what) {
    for (const auto& [name, line] : src.unread()) {
      std::vector<std::string> names;
      for (const auto& p : t.params) names.push_back(p.name);
      std::string near = didYouMean(name, names);
      bool duplicate = t.paramIndex(name) >= 0 || (src.ignoresCase() && t.paramIndexIgnoreCase(name) >= 0);
      if (duplicate) {
        diag_.error({loc.file, line}, prefix(what) + "parameter '" + quoteInput(name) + "' given twice");
      } else if (!near.empty()) {
        diag_.error({loc.file, line},
                    prefix(what) + "parameter '" + quoteInput(name) + "' unknown (did you mean '" + near + "'?)");
      } else {
        // Nothing close: say what the type does take (an INI list by its Count key).
        std::string list;
        for (const auto& p : t.params)
          list += (list.empty() ? "" : ", ") +
                  (p.kind == ParamKind::List && src.ignoresCase() ? listItemName(p.name) + "Count" : p.name);
        diag_.error({loc.file, line}, prefix(what) + "parameter '" + quoteInput(name) + "' unknown (" + t.name +
                                          (names.empty() ? " takes no parameters)" : " takes " + list + ")"));
      }
    }
  }

  void readImport(int index, const SourceLoc& loc) {
    const Component& c = scene_.at(index);
    const TypeSpec* t = c.type;
    const Slot& file_slot = c.slot("File");
    std::string file = std::get<std::string>(file_slot.value());
    const What what(t->name + " '" + c.qkey + "'");
    SourceLoc at = file_slot.set ? file_slot.loc : loc;
    if (file.empty()) {
      diag_.error(at, prefix(what) + "parameter 'File' is required");
      return;
    }
    std::filesystem::path p(file);
    if (p.is_relative()) p = std::filesystem::path(loc.file.str()).parent_path() / p;
    std::string path = p.lexically_normal().string();
    if (too_big_) return;
    if (++imports_ > kMaxImports) {
      too_big_ = true;
      diag_.error(at, prefix(what) + "more than " + std::to_string(kMaxImports) +
                          " imports in all (files that import the same file several times multiply)");
      return;
    }
    if (import_stack_.size() >= kMaxImportDepth) {
      diag_.error(at, prefix(what) + "imports nested deeper than " + std::to_string(kMaxImportDepth) + " files");
      return;
    }
    if (t->import_root == "robot") {
      readUrdf(index, path, at, what);
      return;
    }
    std::error_code ec;
    std::string canon = std::filesystem::weakly_canonical(path, ec).string();
    if (ec) canon = path;
    if (std::find(import_stack_.begin(), import_stack_.end(), canon) != import_stack_.end()) {
      std::string chain;
      for (const auto& f : import_stack_) chain += f + " -> ";
      diag_.error(at, prefix(what) + "cyclic import: " + chain + canon);
      return;
    }
    std::string text, err;
    bool too_large = false;
    if (!readFile(path, kMaxSceneFileBytes, &text, &err, true, &too_large)) {
      diag_.error(at, prefix(what) + "cannot read import '" + quoteInput(path, 400) + "': " + err,
                  too_large ? ErrorKind::InvalidInput : ErrorKind::MissingInput);
      return;
    }
    addFile(path, text);
    int err_line = 0;
    std::shared_ptr<XmlDoc> doc = parseXml(std::move(text), reg_, &err, &err_line, [&path] { return reread(path); });
    if (!doc) {
      diag_.error({path, err_line}, err);
      return;
    }
    std::string root_name;
    std::unique_ptr<Source> root = xmlRoot(doc, &root_name);
    if (root_name != t->import_root) {
      diag_.error({path, root->line()}, "root element is <" + root_name + ">, expected <" + t->import_root +
                                            "> (imported by " + loc.file + ":" + std::to_string(loc.line) + ")");
      return;
    }
    import_stack_.push_back(canon);
    std::unique_ptr<Source> docsrc = xmlDocument(doc);
    // The imported components hang below the importing one: <import key>.<their key>.
    ParamSpec holder;
    holder.name = t->import_root;
    holder.kind = t->import_root == "RefList" ? ParamKind::List : ParamKind::Component;
    std::vector<int> roots;
    if (holder.kind == ParamKind::List) {
      holder.families = {Family::Material, Family::Skin,    Family::Model, Family::Pose,
                         Family::Geom,     Family::Inertia, Family::Motion};
      bool present = false;
      int line = 0;
      for (auto& item : docsrc->list(t->import_root, &present, &line)) {
        Link l = makeLink(item, holder, std::string(item.type), index, scene_.at(index).qkey, path, What("<RefList>"));
        if (l.isRef()) diag_.error(l.loc, "<RefList> items must be components, not Refs");
        if (l.comp >= 0) roots.push_back(l.comp);
      }
    } else {
      holder.families = {t->family == Family::Joint ? Family::Joint : Family::Body};
      SourceLink item = docsrc->component(t->import_root);
      Link l = makeLink(item, holder, std::string(item.type), index, scene_.at(index).qkey, path,
                        What("<" + t->import_root + ">"));
      if (l.isRef()) diag_.error(l.loc, "<" + t->import_root + "> must hold a component, not a Ref");
      if (l.comp >= 0) roots.push_back(l.comp);
    }
    import_stack_.pop_back();
    scene_.at(index).imported = roots;
  }

  /// RCImportURDF (docs/urdf.md): the robot is read now (its meshes and textures found, every
  /// problem at its line in the URDF) and kept in Scene::urdf for the compile step; its links,
  /// and its drives when Drives asks for them, become placeholder components keyed
  /// IMPORTKEY.link and IMPORTKEY.joint, so that Refs (cameras, sensors, schedules) reach them.
  void readUrdf(int index, const std::string& path, const SourceLoc& at, const What& what) {
    std::string text, err;
    bool too_large = false;
    auto pre = preloaded_.find(path);
    if (pre != preloaded_.end()) {
      text = pre->second;
    } else if (!readFile(path, kMaxSceneFileBytes, &text, &err, true, &too_large)) {
      diag_.error(at, prefix(what) + "cannot read URDF '" + quoteInput(path, 400) + "': " + err,
                  too_large ? ErrorKind::InvalidInput : ErrorKind::MissingInput);
      return;
    }
    addFile(path, text);
    const Component& c = scene_.at(index);
    UrdfPackages packages;
    const Slot& ps = c.slot("Packages");
    std::string problem;
    if (!parseUrdfPackages(std::get<std::string>(ps.value()), &packages, &problem)) {
      diag_.error(ps.loc, prefix(what) + "parameter 'Packages': " + problem);
      return;
    }
    for (auto& [name, dir] : packages)  // relative to the scene file that says it
      if (std::filesystem::path(dir).is_relative())
        dir = (std::filesystem::path(ps.loc.file.str()).parent_path() / dir).lexically_normal().string();
    packages.insert(packages.end(), reg_.packages().begin(), reg_.packages().end());
    std::shared_ptr<const UrdfRobot> robot = simbob::readUrdf(text, path, packages, diag_);
    if (!robot) return;
    for (const std::string& f : robot->files) scene_.files.push_back(f);
    scene_.urdf[index] = robot;
    const std::string qkey = c.qkey;
    const TypeSpec* drive = reg_.find(urdfDriveType(std::get<EnumValue>(c.slot("Drives").value()).value));
    std::vector<int> made;
    std::set<std::string> names;
    for (const UrdfLink& l : robot->links) {
      names.insert(urdfKey(l.name));
      made.push_back(build(reg_.find("URDFLink"), nullptr, urdfKey(l.name), true, index, qkey, {path, l.line}));
    }
    for (const UrdfJoint& j : robot->joints)
      if (drive && urdfJointDriven(j) && !names.count(urdfKey(j.name)))
        made.push_back(build(drive, nullptr, urdfKey(j.name), true, index, qkey, {path, j.line}));
    scene_.at(index).imported = made;
  }

  void preload(const std::string& path, std::string text) { preloaded_[path] = std::move(text); }

  void addFile(const std::string& path, const std::string& text) {
    text_bytes_ += text.size();
    scene_.files.push_back(path);
    hash_ = fnv1aWords(hash_, text);
    scene_.content_hash = hex64(hash_);
  }

  void pushFile(const std::string& canon) { import_stack_.push_back(canon); }

 private:
  bool parseInto(const ParamSpec& p, std::string_view text, Value* out, const SourceLoc& loc, const What& what) {
    ParseResult r = parseParam(p, text);
    if (!r) {
      diag_.error(loc, prefix(what) + r.error);
      return false;
    }
    *out = std::move(*r.value);
    return true;
  }

  // A long list (a scene's ComponentList) adds about as many components per item as its first
  // items did: reserve for the rest once, with a quarter to spare, instead of letting comps double
  // (and be copied) near its largest. Every component takes some text, which caps the guess.
  void reserveComponents(size_t comps_before, size_t done, size_t total) {
    const size_t per_item = (scene_.comps.size() - comps_before + done - 1) / done;
    const size_t want = scene_.comps.size() + per_item * (total - done) * 5 / 4;
    scene_.comps.reserve(std::min(want, scene_.comps.size() + text_bytes_ / kMinComponentBytes));
    scene_.by_qkey.reserve(scene_.comps.capacity(), scene_.comps);
  }

  void registerKey(int index) {
    const Component& c = scene_.at(index);
    // Below a component whose key was a duplicate every key repeats too: report the first only.
    if (c.parent >= 0 && duplicates_.count(c.parent)) {
      duplicates_.insert(index);
      return;
    }
    const int earlier = scene_.addKey(index);
    if (earlier >= 0) {
      duplicates_.insert(index);
      const Component& first = scene_.at(earlier);
      diag_.error(c.loc, c.type->name + ": duplicate key '" + c.qkey + "' (first used at " + first.loc.file + ":" +
                             std::to_string(first.loc.line) + "); give it a different Key" +
                             (c.has_key ? ""
                                        : " (a component without Key is keyed by its parameter name, or in a "
                                          "list by its type name)"));
    }
  }

  // Parameters left out take their default component. Defaults never change, so one instance
  // per type serves every body: a 100,000-body scene does not carry 500,000 copies of them.
  int sharedDefault(const std::string& type) {
    auto it = shared_defaults_.find(type);
    if (it != shared_defaults_.end()) return it->second;
    int index = build(reg_.find(type), nullptr, "", false, -1, "", SourceLoc{}, false);
    shared_defaults_.emplace(type, index);
    return index;
  }

  Link makeLink(SourceLink& l, const ParamSpec& p, const std::string& default_key, int parent,
                const std::string& parent_qkey, const FileName& file, const What& what) {
    Link link;
    link.loc = {file, l.line};
    if (!l.error.empty()) {
      diag_.error(link.loc, prefix(what) + l.error);
      return link;
    }
    if (!l.ref.empty()) {
      link.ref = std::string(l.ref);
      return link;
    }
    if (!l.macro.empty()) {
      link.macro = std::string(l.macro);
      const MacroSpec* m = reg_.findMacro(l.macro);
      if (!m) {
        std::vector<std::string> names;
        for (const auto& mm : reg_.macros()) names.push_back(mm.name);
        std::string near = didYouMean(l.macro, names);
        diag_.error(link.loc, prefix(what) + "unknown Macro '" + std::string(l.macro) + "'" +
                                  (near.empty() ? "" : " (did you mean '" + near + "'?)"));
        return link;
      }
      if (!familyAccepted(p, m->family)) {
        diag_.error(link.loc, prefix(what) + "Macro '" + m->name + "' makes a " + familyName(m->family) +
                                  ", parameter '" + p.name + "' needs a " + familiesText(p));
        return link;
      }
      // A Macro list item has no type element: it is keyed by the type it creates.
      link.comp = build(reg_.find(m->type), nullptr, default_key.empty() ? m->type : default_key, false, parent,
                        parent_qkey, link.loc);
      return link;
    }
    const TypeSpec* t = reg_.find(l.type);
    if (!t && l.body && l.body->ignoresCase()) t = reg_.findIgnoreCase(l.type);
    if (!t || t->family == Family::Struct) {
      const bool plugin_family =  // the families plug-ins add to: controllers, sensors and actuators
          std::find(p.families.begin(), p.families.end(), Family::Controller) != p.families.end() ||
          std::find(p.families.begin(), p.families.end(), Family::Periphery) != p.families.end();
      diag_.error(link.loc, prefix(what) + reg_.unknownTypeMessage(l.type, plugin_family));
      return link;
    }
    if (!familyAccepted(p, t->family)) {
      diag_.error(link.loc, prefix(what) + "parameter '" + p.name + "' needs a " + familiesText(p) + ", got " +
                                t->name + " (a " + familyName(t->family) + ")");
      return link;
    }
    std::string key = l.has_key ? std::string(l.key) : default_key;
    if (l.has_key && (key.empty() || key.find('.') != std::string::npos)) {
      diag_.error(link.loc, t->name + ": Key '" + key + "' must be non-empty and contain no '.'");
      key = default_key;
    }
    // A line break in a key would break the INI writer's "Key = ..." line (and every message);
    // XML cannot hold other control characters.
    auto control = [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; };
    if (l.has_key && std::any_of(key.begin(), key.end(), control)) {
      diag_.error(link.loc, t->name + ": Key must not contain control characters (line breaks, tabs)");
      key = default_key;
    }
    link.comp = build(t, l.body.get(), key, l.has_key, parent, parent_qkey, link.loc);
    return link;
  }

  const Registry& reg_;
  Scene& scene_;
  Diagnostics& diag_;
  std::vector<std::string> import_stack_;
  uint64_t hash_ = 1469598103934665603ull;
  size_t text_bytes_ = 0;                           // of every file read
  static constexpr size_t kEstimateAfter = 16;      // list items built before reserving for the rest
  static constexpr size_t kMinComponentBytes = 16;  // text a component takes at least ("<A Macro=\"B\"/>")
  int depth_ = 0;
  int imports_ = 0;
  bool nesting_reported_ = false;
  bool too_big_ = false;                          // a size limit was crossed: stop building (one error, not thousands)
  std::set<int> duplicates_;                      // components whose qualified key was taken already
  std::map<std::string, int> shared_defaults_;    // default component of each type
  std::map<std::string, std::string> preloaded_;  // file -> text already in hand (a bare URDF)
};

// Refs that connect rather than contain (a joint's Body, a drive's Joint, a camera's Body...):
// following them is not a containment cycle.
bool isConnection(Family target) {
  return target == Family::Body || target == Family::Joint || target == Family::Periphery ||
         target == Family::Controller;
}

// A Ref IMPORTKEY.JOINT that names no component may name a URDF joint that got no drive: say
// why ("" when it names none).
std::string urdfJointWithoutDrive(const Scene& scene, const std::string& ref) {
  for (const auto& [index, robot] : scene.urdf) {
    const std::string& key = scene.at(index).qkey;
    if (ref.size() <= key.size() + 1 || ref.compare(0, key.size(), key) != 0 || ref[key.size()] != '.') continue;
    const std::string name = ref.substr(key.size() + 1);
    for (const UrdfJoint& j : robot->joints) {
      if (urdfKey(j.name) != name) continue;
      const std::string joint = "names joint '" + quoteInput(j.name) + "' of URDF robot '" + key + "', ";
      if (j.mimic >= 0)
        return joint + "a mimic joint: it has no drive (it follows joint '" +
               quoteInput(robot->joints[static_cast<size_t>(j.mimic)].name) + "'; command that one)";
      if (!urdfJointDriven(j)) return joint + "which does not move: it has no drive";
      return joint + "which has no drive: RCImportURDF '" + key + "' has Drives none";
    }
  }
  return "";
}

void resolveRefs(Scene& scene, Diagnostics& diag) {
  std::vector<std::string> keys;  // for "did you mean", made on the first unknown Ref
  for (size_t ci = 0; ci < scene.comps.size(); ++ci) {
    Component& c = scene.comps[ci];
    for (size_t pi = 0; pi < c.slots.size(); ++pi) {
      const ParamSpec& p = c.type->params[pi];
      auto resolve = [&](Link& l) {
        if (!l.isRef()) return;
        const int target_index = scene.find(l.ref.str());
        if (target_index < 0) {
          // In key order, so that the nearest of equals is always the same.
          if (keys.empty()) keys = scene.sortedKeys();
          const std::string why = urdfJointWithoutDrive(scene, l.ref.str());
          if (!why.empty()) {
            diag.error(l.loc, c.type->name + " '" + c.qkey + "': Ref '" + l.ref + "' " + why);
            return;
          }
          std::string near = didYouMean(l.ref.str(), keys);
          diag.error(l.loc, c.type->name + " '" + c.qkey + "': Ref '" + l.ref + "' names no component" +
                                (near.empty() ? "" : " (did you mean '" + near + "'?)"));
          return;
        }
        const Component& target = scene.at(target_index);
        if (!familyAccepted(p, target.type->family)) {
          diag.error(l.loc, c.type->name + " '" + c.qkey + "': Ref '" + l.ref + "' names a " + target.type->name +
                                ", parameter '" + p.name + "' needs a " + familiesText(p));
          return;
        }
        l.comp = target_index;
      };
      if (Link* l = c.slots[pi].linkIf()) resolve(*l);
      if (std::vector<Link>* items = c.slots[pi].listIf())
        for (auto& l : *items) resolve(l);
    }
  }
}

// Containment must be a tree or DAG: a Ref that leads back to a component that contains it
// would make the compile step recurse forever.
void checkCycles(const Scene& scene, Diagnostics& diag) {
  enum State : uint8_t { White, Grey, Black };
  std::vector<State> state(scene.comps.size(), White);
  struct Frame {
    int comp;
    size_t slot;
    size_t item;
  };
  std::vector<Frame> stack;  // one for every start: most components are reached from a parent
  for (size_t start = 0; start < scene.comps.size(); ++start) {
    if (state[start] != White) continue;
    stack.push_back({static_cast<int>(start), 0, 0});
    state[start] = Grey;
    while (!stack.empty()) {
      Frame& f = stack.back();
      const Component& c = scene.at(f.comp);
      const Link* next = nullptr;
      while (!next && f.slot < c.slots.size()) {
        const Slot& s = c.slots[f.slot];
        const ParamKind kind = c.type->params[f.slot].kind;
        if (kind == ParamKind::Value) {  // a value links to nothing
          ++f.slot;
          continue;
        }
        const std::vector<Link>* items = nullptr;
        if (kind == ParamKind::List) items = &s.list();
        if (items) {
          if (f.item < items->size())
            next = &(*items)[f.item++];
          else {
            ++f.slot;
            f.item = 0;
          }
        } else {
          if (f.item == 0) {
            next = &s.link();
            f.item = 1;
          } else {
            ++f.slot;
            f.item = 0;
          }
        }
        if (next && (next->comp < 0 || (next->isRef() && isConnection(scene.at(next->comp).type->family))))
          next = nullptr;
      }
      if (!next) {
        state[static_cast<size_t>(f.comp)] = Black;
        stack.pop_back();
        continue;
      }
      auto target = static_cast<size_t>(next->comp);
      if (state[target] == Grey) {
        diag.error(next->loc,
                   c.type->name + " '" + c.qkey + "': cyclic Ref '" + next->ref + "' (it contains " + c.qkey + ")");
        state[target] = Black;  // report each cycle once
        continue;
      }
      if (state[target] == White) {
        state[target] = Grey;
        stack.push_back({next->comp, 0, 0});
      }
    }
  }
}

/// A bare URDF is a scene of its own (docs/urdf.md): a ground plane at the robot's z = 0 and one
/// RCImportURDF keyed by the robot's name, so that both ways share one path.
std::string urdfScene(const std::string& name, const std::string& text) {
  pugi::xml_document doc;
  std::string robot;
  if (doc.load_buffer(text.data(), text.size())) robot = doc.document_element().attribute("name").value();
  robot = urdfKey(robot.empty() ? "robot" : robot);
  const std::string ground = robot == "Ground" ? "Floor" : "Ground";
  return "<Simulation><ComponentList><RCGround Key=\"" + ground + "\"/><RCImportURDF Key=\"" + escapeXml(robot) +
         "\"><File Value=\"" + escapeXml(std::filesystem::path(name).filename().string()) +
         "\"/><AboveGround Value=\"true\"/></RCImportURDF></ComponentList></Simulation>";
}

// `given` is the caller's text when it came from memory; a file's is read again if a message
// needs it as it was (see parseXml).
bool loadFromText(std::string text, const std::string& name, Format format, const Registry& reg, Scene* scene,
                  Diagnostics& diag, const std::string* given) {
  *scene = Scene{};
  scene->path = name;
  if (text.size() > kMaxSceneFileBytes) {  // scene text from memory (Python's from_text) has a file's limit
    diag.error({name, 0}, "cannot read scene: larger than " + std::to_string(kMaxSceneFileBytes >> 20) + " MiB",
               ErrorKind::InvalidInput);
    return false;
  }
  Builder b(reg, *scene, diag);
  std::string made;  // the scene made around a bare URDF, parsed in the file's place
  if (format == Format::Xml && looksLikeUrdf(name, text)) {
    b.preload(std::filesystem::path(name).lexically_normal().string(), text);
    made = urdfScene(name, text);
    text = made;
    scene->bare_urdf = true;
  } else {
    b.addFile(name, text);
  }
  std::error_code ec;
  std::string canon = std::filesystem::weakly_canonical(name, ec).string();
  b.pushFile(ec ? name : canon);
  std::string err;
  int err_line = 0;
  std::unique_ptr<Source> root;
  std::shared_ptr<XmlDoc> xml;
  std::shared_ptr<IniDoc> ini;
  if (format == Format::Xml) {
    xml = parseXml(std::move(text), reg, &err, &err_line, [&] {
      if (!made.empty()) return made;
      return given ? *given : reread(name);
    });
    if (!xml) {
      diag.error({name, err_line}, err);
      return false;
    }
    std::string root_name;
    root = xmlRoot(xml, &root_name);
    if (root_name != "Simulation") {
      diag.error({name, root->line()}, "root element is <" + root_name + ">, expected <Simulation>");
      return false;
    }
  } else {
    ini = parseIni(text, &err, &err_line);
    if (!ini) {
      diag.error({name, err_line}, err);
      return false;
    }
    root = iniRoot(ini);
  }
  int top = b.build(reg.find("Simulation"), root.get(), "", false, -1, "", {name, root->line()});
  const Component& sim = scene->at(top);
  scene->settings = sim.slot("SceneSettings").link().comp;
  scene->cameras = sim.slot("CameraList").list();
  scene->components = sim.slot("ComponentList").list();
  if (!diag.ok()) return false;
  resolveRefs(*scene, diag);
  if (!diag.ok()) return false;
  checkCycles(*scene, diag);
  // The lists above were copied before Refs were resolved.
  scene->cameras = sim.slot("CameraList").list();
  scene->components = sim.slot("ComponentList").list();
  return diag.ok();
}

}  // namespace

bool loadSceneFromText(const std::string& text, const std::string& name, Format format, const Registry& reg,
                       Scene* scene, Diagnostics& diag) {
  return loadFromText(text, name, format, reg, scene, diag, &text);
}

Format sceneFormatOf(const std::string& path) {
  const bool ini = path.size() >= 4 && equalsIgnoreCase(std::string_view(path).substr(path.size() - 4), ".ini");
  return ini ? Format::Ini : Format::Xml;
}

bool loadScene(const std::string& path, const Registry& reg, Scene* scene, Diagnostics& diag) {
  std::string text, err;
  bool too_large = false;
  if (!readFile(path, kMaxSceneFileBytes, &text, &err, true, &too_large)) {
    // Too large is an input limit (65); the rest means the file cannot be read (66).
    diag.error({path, 0}, "cannot read scene: " + err, too_large ? ErrorKind::InvalidInput : ErrorKind::MissingInput);
    return false;
  }
  return loadFromText(std::move(text), path, sceneFormatOf(path), reg, scene, diag, nullptr);
}

bool loadStructIni(const std::string& path, const Registry& reg, const std::string& struct_type, Scene* holder,
                   int* comp, Diagnostics& diag) {
  std::string text, err;
  if (!readFile(path, kMaxSceneFileBytes, &text, &err, true)) {
    diag.error({path, 0}, "cannot read settings: " + err, ErrorKind::MissingInput);
    return false;
  }
  int err_line = 0;
  std::shared_ptr<IniDoc> ini = parseIni(text, &err, &err_line);
  if (!ini) {
    diag.error({path, err_line}, err);
    return false;
  }
  *holder = Scene{};
  holder->path = path;
  Builder b(reg, *holder, diag);
  std::unique_ptr<Source> root = iniRoot(ini);
  *comp = b.build(reg.find(struct_type), root.get(), "", false, -1, "", {path, 1});
  return diag.ok();
}

}  // namespace simbob
