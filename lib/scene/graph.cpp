// Component accessors and the scene writers (XML 4.2, INI 4.1), both driven by the same walk
// over the registry's parameter tables.
#include "simbob/graph.h"

#include "scene/source.h"

#include <pugixml.hpp>
#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace simbob {

const Value& Slot::emptyValue() {
  static const Value v;
  return v;
}
const Link& Slot::emptyLink() {
  static const Link l;
  return l;
}
const std::vector<Link>& Slot::emptyList() {
  static const std::vector<Link> l;
  return l;
}

namespace {
const Slot& missingSlot() {
  static const Slot s;
  return s;
}
}  // namespace

namespace {
// Where `qkey` is in a key index's slots, or the empty slot where it would go: the one probe
// loop of find, insert and rehash.
size_t probe(const std::vector<int32_t>& slots, std::string_view qkey, const std::vector<Component>& comps) {
  const size_t mask = slots.size() - 1;
  size_t i = NameTable::hash(qkey) & mask;
  while (slots[i] != 0 && comps[static_cast<size_t>(slots[i] - 1)].qkey != qkey) i = (i + 1) & mask;
  return i;
}
}  // namespace

int KeyIndex::find(std::string_view qkey, const std::vector<Component>& comps) const {
  return slots_.empty() ? -1 : slots_[probe(slots_, qkey, comps)] - 1;
}

int KeyIndex::insert(int index, const std::vector<Component>& comps) {
  if ((size_ + 1) * 2 > slots_.size()) rehash(slots_.empty() ? 64 : slots_.size() * 2, comps);
  const size_t i = probe(slots_, comps[static_cast<size_t>(index)].qkey, comps);
  if (slots_[i] != 0) return slots_[i] - 1;
  slots_[i] = index + 1;
  ++size_;
  return -1;
}

void KeyIndex::reserve(size_t n, const std::vector<Component>& comps) {
  size_t slots = slots_.empty() ? 64 : slots_.size();
  while (n * 2 > slots) slots *= 2;
  if (slots > slots_.size()) rehash(slots, comps);
}

// Every key hashed again into `slots` slots (a power of two).
void KeyIndex::rehash(size_t slots, const std::vector<Component>& comps) {
  std::vector<int32_t> old = std::move(slots_);
  slots_.assign(slots, 0);
  for (int32_t e : old)
    if (e != 0) slots_[probe(slots_, comps[static_cast<size_t>(e - 1)].qkey, comps)] = e;  // keys are distinct
}

std::vector<int> KeyIndex::indices() const {
  std::vector<int> out;
  out.reserve(size_);
  for (int32_t e : slots_)
    if (e != 0) out.push_back(e - 1);
  return out;
}

std::vector<std::string> Scene::sortedKeys() const {
  std::vector<std::string> keys;
  keys.reserve(by_qkey.size());
  for (int i : by_qkey.indices()) keys.push_back(at(i).qkey);
  std::sort(keys.begin(), keys.end());
  return keys;
}

const Slot& Component::slot(std::string_view param) const {
  int i = type->paramIndex(param);
  return i < 0 ? missingSlot() : slots[static_cast<size_t>(i)];
}
Slot& Component::slot(std::string_view param) {
  int i = type->paramIndex(param);
  return slots.at(static_cast<size_t>(i));
}
void Component::missingParam(const ParamName& p) const {
  throw std::logic_error("internal: " + type->name + " has no parameter '" + p.name + "'");
}
uint32_t Component::get(EnumParam p) const {
  const Value& v = typedSlot(p).value();
  if (auto* e = std::get_if<EnumValue>(&v)) return e->value;
  return std::get<BitmaskValue>(v).bits;
}

namespace {

/// What a writer must do; the walk below decides what to write.
class Emitter {
 public:
  virtual ~Emitter() = default;
  virtual void value(const std::string& name, const std::string& text) = 0;
  virtual void reference(const std::string& name, const char* attr, const std::string& target) = 0;
  virtual void beginComponent(const std::string& name, const std::string& type, const std::string* key) = 0;
  virtual void beginStruct(const std::string& name) = 0;
  virtual void beginList(const std::string& name, size_t count) = 0;
  virtual void listItem(size_t i, const std::string& type, const std::string* key) = 0;
  virtual void listReference(size_t i, const char* attr, const std::string& target) = 0;
  virtual void end() = 0;
};

class Walker {
 public:
  Walker(const Scene& s, Emitter& e, bool fill) : scene_(s), em_(e), fill_(fill) {}

  void body(int ci) {
    const Component& c = scene_.at(ci);
    for (size_t pi = 0; pi < c.slots.size(); ++pi) {
      const ParamSpec& p = c.type->params[pi];
      const Slot& s = c.slots[pi];
      if (!s.set && !fill_) continue;
      switch (p.kind) {
        case ParamKind::Value:
          em_.value(p.name, formatValue(p.type, s.value(), p.table));
          break;
        case ParamKind::Component:
          if (s.link().isRef()) {
            em_.reference(p.name, "Ref", s.link().ref);
          } else if (!s.link().macro.empty()) {
            em_.reference(p.name, "Macro", s.link().macro);
          } else if (s.link().comp >= 0) {
            const Component& child = scene_.at(s.link().comp);
            const std::string key = child.key();
            em_.beginComponent(p.name, child.type->name, child.has_key ? &key : nullptr);
            body(s.link().comp);
            em_.end();
          }
          break;
        case ParamKind::Struct:
          if (s.link().comp >= 0) {
            em_.beginStruct(p.name);
            body(s.link().comp);
            em_.end();
          }
          break;
        case ParamKind::List:
          em_.beginList(p.name, s.list().size());
          for (size_t i = 0; i < s.list().size(); ++i) {
            const Link& l = s.list()[i];
            if (l.isRef()) {
              em_.listReference(i, "Ref", l.ref);
            } else if (!l.macro.empty()) {
              em_.listReference(i, "Macro", l.macro);
            } else if (l.comp >= 0) {
              const Component& child = scene_.at(l.comp);
              const std::string key = child.key();
              em_.listItem(i, child.type->name, child.has_key ? &key : nullptr);
              body(l.comp);
              em_.end();
            }
          }
          em_.end();
          break;
      }
    }
  }

 private:
  const Scene& scene_;
  Emitter& em_;
  bool fill_;
};

class XmlEmitter : public Emitter {
 public:
  explicit XmlEmitter(pugi::xml_node root) { stack_.push_back({root, ""}); }
  void value(const std::string& name, const std::string& text) override {
    top().append_child(name.c_str()).append_attribute("Value") = text.c_str();
  }
  void reference(const std::string& name, const char* attr, const std::string& target) override {
    top().append_child(name.c_str()).append_attribute(attr) = target.c_str();
  }
  void beginComponent(const std::string& name, const std::string& type, const std::string* key) override {
    pugi::xml_node t = top().append_child(name.c_str()).append_child(type.c_str());
    if (key) t.append_attribute("Key") = key->c_str();
    stack_.push_back({t, ""});
  }
  void beginStruct(const std::string& name) override { stack_.push_back({top().append_child(name.c_str()), ""}); }
  void beginList(const std::string& name, size_t) override {
    stack_.push_back({top().append_child(name.c_str()), listItemName(name)});
  }
  void listItem(size_t, const std::string& type, const std::string* key) override {
    pugi::xml_node t = top().append_child(type.c_str());
    if (key) t.append_attribute("Key") = key->c_str();
    stack_.push_back({t, ""});
  }
  void listReference(size_t, const char* attr, const std::string& target) override {
    // A Ref in a list needs a wrapper element: the list's item name ("Component" in ComponentList).
    top().append_child(stack_.back().item.c_str()).append_attribute(attr) = target.c_str();
  }
  void end() override { stack_.pop_back(); }

 private:
  struct Open {
    pugi::xml_node node;
    std::string item;  // lists: the wrapper name of Ref items
  };
  pugi::xml_node top() { return stack_.back().node; }
  std::vector<Open> stack_;
};

std::string iniQuote(const std::string& v) {
  bool quote = v.empty() || v.front() == '"' || v.back() == '"' || v.front() == ' ' || v.back() == ' ' ||
               v.front() == '\t' || v.back() == '\t' || v.front() == '\r' || v.back() == '\r';
  return quote ? "\"" + v + "\"" : v;
}

class IniEmitter : public Emitter {
 public:
  explicit IniEmitter(std::string& out) : out_(out) {}
  void value(const std::string& name, const std::string& text) override { line(name, text); }
  void reference(const std::string& name, const char* attr, const std::string& target) override {
    line(name + "." + attr, target);
  }
  void beginComponent(const std::string& name, const std::string& type, const std::string* key) override {
    push(name, "");
    line("Type", type);
    if (key) line("Key", *key);
  }
  void beginStruct(const std::string& name) override { push(name, ""); }
  void beginList(const std::string& name, size_t count) override {
    std::string base = listItemName(name);
    line(base + "Count", std::to_string(count));
    // Items are <prefix>.<base><i>: the list itself adds no prefix level.
    stack_.push_back({prefix(), base});
  }
  void listItem(size_t i, const std::string& type, const std::string* key) override {
    if (stack_.size() == 1) out_ += "\n";  // a blank line between top-level items
    push(stack_.back().item + std::to_string(i), "");
    line("Type", type);
    if (key) line("Key", *key);
  }
  void listReference(size_t i, const char* attr, const std::string& target) override {
    line(stack_.back().item + std::to_string(i) + "." + attr, target);
  }
  void end() override { stack_.pop_back(); }

 private:
  struct Open {
    std::string prefix;
    std::string item;
  };
  std::string prefix() const { return stack_.empty() ? std::string() : stack_.back().prefix; }
  void push(const std::string& name, const std::string& item) {
    std::string base = prefix();
    stack_.push_back({base.empty() ? name : base + "." + name, item});
  }
  void line(const std::string& name, const std::string& v) {
    std::string base = prefix();
    out_ += base.empty() ? name : base + "." + name;
    out_ += " = ";
    out_ += iniQuote(v);
    out_ += "\n";
  }
  std::string& out_;
  std::vector<Open> stack_;
};

}  // namespace

std::string writeScene(const Scene& scene, Format format, bool fill_defaults) {
  int root = -1;
  for (size_t i = 0; i < scene.comps.size(); ++i)
    if (scene.comps[i].parent < 0 && scene.comps[i].type->name == "Simulation") {
      root = static_cast<int>(i);
      break;
    }
  if (root < 0) return {};
  if (format == Format::Xml) {
    pugi::xml_document doc;
    pugi::xml_node decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    pugi::xml_node sim = doc.append_child("Simulation");
    XmlEmitter em(sim);
    Walker(scene, em, fill_defaults).body(root);
    std::ostringstream os;
    doc.save(os, "  ", pugi::format_default, pugi::encoding_utf8);
    return os.str();
  }
  std::string out;
  IniEmitter em(out);
  Walker(scene, em, fill_defaults).body(root);
  return out;
}

}  // namespace simbob
