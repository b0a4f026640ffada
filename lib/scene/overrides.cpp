// `--set KEY.PARAM=VALUE`: overrides applied to the component graph before compiling.
#include "simbob/overrides.h"

#include <algorithm>

namespace simbob {

namespace {

bool isRoot(const Component& c) { return c.parent < 0 && c.type && c.type->name == "Simulation"; }

int rootIndex(const Scene& scene) {
  for (size_t i = 0; i < scene.comps.size(); ++i)
    if (isRoot(scene.comps[i])) return static_cast<int>(i);
  return -1;
}

// How the loader names a component in messages: "RCGenericMaterial 'Crate.Material'".
std::string what(const Component& c, const std::string& key) {
  return c.type->name + " '" + (c.qkey.empty() ? key : c.qkey) + "'";
}

/// Whether KEY is a camera or lies inside one ("Side", "Side.Pose"): some prefix of it, cut at a
/// dot, is the key of a camera component.
bool namesCamera(const Scene& scene, const std::string& key) {
  for (size_t end = key.size(); end != std::string::npos && end > 0; end = key.rfind('.', end - 1)) {
    const int i = scene.find(std::string_view(key).substr(0, end));
    if (i >= 0 && scene.at(i).type->family == Family::Camera) return true;
  }
  return false;
}

class Resolver {
 public:
  explicit Resolver(Scene& scene) : scene_(scene) {}

  /// The component KEY names, or -1. Follows component-valued parameters from the longest
  /// known prefix, so `Crate.Material` reaches a Ref's target or (a copy of) a default.
  int resolve(const std::string& key) {
    if (const int i = scene_.find(key); i >= 0) return i;
    const size_t dot = key.rfind('.');
    const int parent = dot == std::string::npos ? rootIndex(scene_) : resolve(key.substr(0, dot));
    if (parent < 0) return -1;
    const std::string name = dot == std::string::npos ? key : key.substr(dot + 1);
    const Component& pc = scene_.at(parent);
    const int pi = pc.type->paramIndex(name);
    if (pi < 0) return -1;
    const ParamKind kind = pc.type->params[static_cast<size_t>(pi)].kind;
    if (kind != ParamKind::Component && kind != ParamKind::Struct) return -1;
    const Link& l = pc.slots[static_cast<size_t>(pi)].link();
    if (l.comp < 0) return -1;
    if (l.isRef() || scene_.at(l.comp).parent == parent) return l.comp;
    // A left-out parameter's default is one component shared by every body that left it out:
    // give this one a copy of its own, so the override reaches it alone.
    Component copy = scene_.at(l.comp);
    copy.setKey(dot == std::string::npos ? std::string() : key.substr(0, dot), name);  // qkey == key
    copy.parent = parent;
    scene_.comps.push_back(std::move(copy));
    const int index = static_cast<int>(scene_.comps.size() - 1);
    scene_.at(parent).slots[static_cast<size_t>(pi)].link().comp = index;
    scene_.addKey(index);
    return index;
  }

 private:
  Scene& scene_;
};

}  // namespace

bool parseOverride(std::string_view text, Override* out, std::string* error) {
  const size_t eq = text.find('=');
  const std::string_view lhs = text.substr(0, eq);
  const size_t dot = lhs.rfind('.');
  if (eq == std::string_view::npos || dot == std::string_view::npos || dot == 0 || dot + 1 == lhs.size()) {
    *error =
        "expected KEY.PARAM=VALUE (a component key as `simbob dump` shows it, '.', a parameter name, '=', "
        "the value as in the scene file), got '" +
        quoteInput(text) + "'";
    return false;
  }
  out->text = std::string(text);
  out->key = std::string(lhs.substr(0, dot));
  out->param = std::string(lhs.substr(dot + 1));
  out->value = std::string(text.substr(eq + 1));
  out->place = "--set " + out->text;
  return true;
}

bool applyOverrides(Scene& scene, const std::vector<Override>& overrides, Diagnostics& diag) {
  Resolver resolver(scene);
  for (const Override& o : overrides) {
    const SourceLoc at{o.place, o.line};
    const int index = resolver.resolve(o.key);
    if (index < 0) {
      // In key order: of equally near keys, the first.
      const std::vector<std::string> keys = scene.sortedKeys();
      const std::string near = didYouMean(o.key, keys);
      diag.error(at, "no component '" + quoteInput(o.key) + "' in " + scene.path +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)"));
      continue;
    }
    Component& c = scene.at(index);
    if (o.cameras_only && !namesCamera(scene, o.key)) {
      diag.error(at, what(c, o.key) + " is no camera: a DocumentIni sets camera parameters only (guide 3.3.1)");
      continue;
    }
    const int pi = c.type->paramIndex(o.param);
    if (const std::string* advice = c.type->retiredAdvice(o.param); pi < 0 && advice) {
      diag.error(at, what(c, o.key) + ": parameter '" + quoteInput(o.param) + "' removed: " + *advice);
      continue;
    }
    if (pi < 0) {
      std::vector<std::string> names;
      for (const auto& p : c.type->params) names.push_back(p.name);
      const std::string near = didYouMean(o.param, names);
      diag.error(at, what(c, o.key) + ": parameter '" + quoteInput(o.param) + "' unknown" +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)"));
      continue;
    }
    const ParamSpec& p = c.type->params[static_cast<size_t>(pi)];
    if (p.kind != ParamKind::Value) {
      diag.error(at, what(c, o.key) + ": parameter '" + p.name + "' is " +
                         (p.kind == ParamKind::List ? "a list" : "a component") +
                         ", not a value; set a parameter inside it (" + o.key + "." + p.name + ".PARAM=VALUE)");
      continue;
    }
    ParseResult r = parseParam(p, o.value);
    if (!r) {
      diag.error(at, what(c, o.key) + ": " + r.error);
      continue;
    }
    Slot& slot = c.slots[static_cast<size_t>(pi)];
    slot.value() = std::move(*r.value);
    slot.set = true;
    slot.loc = at;
  }
  return diag.ok();
}

}  // namespace simbob
