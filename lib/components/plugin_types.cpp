// Plug-in types (docs/plugins.md, simbob/plugin_c.h): registerPlugin checks a plug-in's C
// description and adds each of its types to the Registry -- a controller (its refs, Period,
// its numbers), a sensor or an actuator (a periphery attached like RCRangeSensor to the
// construction's root body with a Pose; a sensor also has Period) -- and lowers the
// peripheries to Model::sensors (SensorKind::Plugin) and Model::actuators (ActuatorDef::Plugin).
// Controllers are lowered with the built-ins (controllers.cpp).
#include <dlfcn.h>

#include <cctype>
#include <deque>
#include <unordered_map>

#include "compile/context.h"
#include "components/families.h"
#include "simbob/plugin.h"

namespace simbob {

namespace {

constexpr LinkParam kPose{"Pose"};
constexpr ValueParam<double> kPeriod{"Period"};

// Bounds on a plug-in's description (docs/plugins.md): far beyond any real type, and small
// enough that a plug-in listing millions of names is refused at once rather than loaded slowly.
constexpr int kMaxTypes = 10000;        // types per plug-in
constexpr int kMaxParams = 10000;       // numbers and refs of one type
constexpr int kMaxQuantities = 100000;  // entries of a sensor's reading: as many as RCLaserScanner's rays

/// Plug-in types live as long as the process: the registry and models point at them.
std::deque<PluginType>& keptTypes() {
  static std::deque<PluginType> types;
  return types;
}

std::string str(const char* s) { return s ? s : ""; }

/// The C description copied and checked; "" or the problem.
std::string describe(const SimbobType& c, const std::string& plugin, PluginType* t) {
  t->c = &c;
  t->plugin = plugin;
  t->name = str(c.name);
  t->doc = str(c.doc);
  t->interface = str(c.interface);
  if (t->name.empty()) return "a type has no name";
  const std::string what = "type '" + t->name + "': ";
  if (c.kind != SIMBOB_CONTROLLER && c.kind != SIMBOB_SENSOR && c.kind != SIMBOB_ACTUATOR)
    return what + "kind " + std::to_string(c.kind) + " is none of SIMBOB_CONTROLLER, SIMBOB_SENSOR, SIMBOB_ACTUATOR";
  if (c.number_count < 0 || (c.number_count > 0 && !c.numbers)) return what + "numbers and number_count disagree";
  if (c.number_count > kMaxParams || (c.kind == SIMBOB_CONTROLLER && c.ref_count > kMaxParams - c.number_count))
    return what + "more than " + std::to_string(kMaxParams) + " numbers and refs (" + std::to_string(c.number_count) +
           " numbers" + (c.kind == SIMBOB_CONTROLLER ? ", " + std::to_string(c.ref_count) + " refs" : "") + ")";
  for (int i = 0; i < c.number_count; ++i) {
    const SimbobNumber& n = c.numbers[i];
    if (!n.name || !*n.name) return what + "number " + std::to_string(i) + " has no name";
    t->numbers.push_back({n.name, n.default_value, str(n.unit), str(n.doc)});
  }
  if (c.kind == SIMBOB_CONTROLLER) {
    if (!c.act) return what + "a controller needs act";
    if (c.ref_count < 0 || (c.ref_count > 0 && !c.refs)) return what + "refs and ref_count disagree";
    for (int i = 0; i < c.ref_count; ++i) {
      const SimbobRef& r = c.refs[i];
      if (!r.name || !*r.name || !r.interface || !*r.interface)
        return what + "ref " + std::to_string(i) + " needs a name and an interface";
      t->refs.push_back({r.name, r.interface, str(r.doc)});
    }
  } else if (c.kind == SIMBOB_SENSOR) {
    if (!c.read) return what + "a sensor needs read";
    if (c.quantity_count < 1 || !c.quantities) return what + "a sensor needs at least one quantity";
    if (c.quantity_count > kMaxQuantities)
      return what + "more than " + std::to_string(kMaxQuantities) + " quantities (" + std::to_string(c.quantity_count) +
             ")";
    for (int i = 0; i < c.quantity_count; ++i) {
      if (!c.quantities[i] || !*c.quantities[i]) return what + "quantity " + std::to_string(i) + " has no name";
      t->quantities.emplace_back(c.quantities[i]);
    }
    if (t->interface == "RCRangeSensor") {
      bool has_max = false;
      for (const PluginNumber& n : t->numbers) has_max = has_max || n.name == "MaxRange";
      if (!has_max) return what + "an RCRangeSensor needs the number MaxRange";
    }
  } else {
    if (!c.apply) return what + "an actuator needs apply";
    if (t->interface.empty()) t->interface = "RCDriver";
  }
  return "";
}

std::string lowerAscii(const std::string& s) {
  std::string out = s;
  for (char& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

/// "" or the first parameter of `t` whose name is taken: by a parameter simbob gives every type
/// of its kind (Period; Pose), or by another of its numbers and refs. Names that differ only in
/// case clash too: INI scenes ignore the case of keys. Linear in the number of names.
std::string clashOf(const PluginType& t) {
  const unsigned kind = t.c->kind;
  const char* kind_word = kind == SIMBOB_CONTROLLER ? "controller" : kind == SIMBOB_SENSOR ? "sensor" : "actuator";
  std::unordered_map<std::string, std::string> taken;  // lowercased name -> what has it
  if (kind != SIMBOB_CONTROLLER) taken.emplace("pose", std::string("simbob's own parameter 'Pose'"));
  if (kind != SIMBOB_ACTUATOR) taken.emplace("period", std::string("simbob's own parameter 'Period'"));
  auto take = [&](const char* what, const std::string& name) -> std::string {
    const std::string me = std::string(what) + " '" + name + "'";
    auto [it, fresh] = taken.emplace(lowerAscii(name), me);
    if (fresh) return "";
    const bool own = it->second.rfind("simbob's", 0) == 0;
    return me + " clashes with " + it->second +
           (own ? " (every plug-in " + std::string(kind_word) + " has it): rename it"
                : " (parameter names must differ, also in case: INI keys ignore it)");
  };
  for (const PluginRef& r : t.refs)
    if (std::string why = take("the ref", r.name); !why.empty()) return why;
  for (const PluginNumber& n : t.numbers)
    if (std::string why = take("the number", n.name); !why.empty()) return why;
  return "";
}

TypeSpec specOf(const PluginType& t) {
  std::vector<ParamSpec> params;
  int kind = 0;
  Family family = Family::Periphery;
  if (t.c->kind == SIMBOB_CONTROLLER) {
    family = Family::Controller;
    kind = int(ControllerKind::Plugin);
    for (const PluginRef& r : t.refs)
      params.push_back(componentParam(LinkParam{r.name.c_str()},
                                      {r.interface == "RCBody" ? Family::Body : Family::Periphery}, "",
                                      r.doc + " (Ref, " + r.interface + ")"));
    params.push_back(number(kPeriod, 0.01, "s", "loop period", Range::Positive));
  } else {
    kind = int(t.c->kind == SIMBOB_SENSOR ? PeripheryKind::PluginSensor : PeripheryKind::PluginActuator);
    params.push_back(componentParam(kPose, {Family::Pose}, "",
                                    "pose of its mount: local coordinates relative to the construction's root body "
                                    "(default: its frame), or global"));
    if (t.c->kind == SIMBOB_SENSOR)
      params.push_back(
          number(kPeriod, 0.0, "s", "time between readings (0: every step); held in between", Range::NonNegative));
  }
  for (const PluginNumber& n : t.numbers)
    params.push_back(number(ValueParam<double>{n.name.c_str()}, n.default_value, n.unit, n.doc));
  TypeSpec spec{t.name, family, kind, std::move(params), {}, t.doc + " (plug-in '" + t.plugin + "')"};
  spec.plugin = &t;
  spec.plugin_name = t.plugin;
  if (t.c->kind == SIMBOB_SENSOR) {
    spec.interfaces = {"RCSensor"};
    if (!t.interface.empty()) spec.interfaces.push_back(t.interface);
  } else if (t.c->kind == SIMBOB_ACTUATOR) {
    spec.interfaces = {t.interface};
  }
  return spec;
}

std::vector<double> numbersOf(const Component& c, const PluginType& t) {
  std::vector<double> v;
  for (const PluginNumber& n : t.numbers) v.push_back(c.get(ValueParam<double>{n.name.c_str()}));
  return v;
}

}  // namespace

std::string pluginWho(const std::string& plugin, const std::string& type) {
  return "plug-in '" + plugin + "', type '" + type + "'";
}

std::string registerPlugin(Registry& reg, const SimbobPlugin& p) {
  const std::string plugin = str(p.name);
  if (p.type_count < 0 || (p.type_count > 0 && !p.types)) return "types and type_count disagree";
  if (p.type_count > kMaxTypes)
    return "more than " + std::to_string(kMaxTypes) + " types (" + std::to_string(p.type_count) + ")";
  for (int i = 0; i < p.type_count; ++i) {
    PluginType t;
    std::string problem = describe(p.types[i], plugin, &t);
    if (problem.empty() && !(problem = clashOf(t)).empty()) problem = "type '" + t.name + "': " + problem;
    if (!problem.empty()) return problem;
    keptTypes().push_back(std::move(t));
    if (!reg.add(specOf(keptTypes().back()))) return reg.problems().back();
  }
  return "";
}

bool loadPluginLibrary(Registry& reg, const std::string& path, Error* error) {
  auto fail = [&](ErrorKind kind, const std::string& what) {
    *error = {kind, {path, 0}, what};
    return false;
  };
  // RTLD_NOW: a missing symbol is an error here, not a crash in the middle of a run.
  void* lib = dlopen(path.find('/') == std::string::npos ? ("./" + path).c_str() : path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    const char* e = dlerror();
    return fail(ErrorKind::MissingInput, std::string("cannot load the plug-in: ") + (e ? e : "dlopen failed"));
  }
  void* sym = dlsym(lib, "simbob_plugin_v2");
  if (!sym && dlsym(lib, "simbob_plugin_v1"))
    return fail(ErrorKind::InvalidInput,
                "built for plug-in ABI 1 (the C++ ABI, entry point simbob_plugin_v1), which this simbob no longer "
                "loads: rebuild it against simbob/plugin_c.h or simbob/plugin.hpp (docs/plugins.md)");
  if (!sym)
    return fail(ErrorKind::InvalidInput,
                "not a simbob plug-in: it has no entry point simbob_plugin_v2 (see simbob/plugin_c.h)");
  using Entry = const SimbobPlugin* (*)();
  const SimbobPlugin* p = reinterpret_cast<Entry>(sym)();  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
  if (!p) return fail(ErrorKind::InvalidInput, "simbob_plugin_v2 returned null");
  if (p->abi_version != SIMBOB_PLUGIN_ABI_VERSION)
    return fail(ErrorKind::InvalidInput, "plug-in ABI version " + std::to_string(p->abi_version) +
                                             ", but this simbob loads version " +
                                             std::to_string(SIMBOB_PLUGIN_ABI_VERSION) +
                                             " (rebuild it against this simbob's simbob/plugin_c.h)");
  const std::string problem = registerPlugin(reg, *p);
  if (!problem.empty())
    return fail(ErrorKind::InvalidInput, "plug-in '" + str(p->name) + "' could not register its types: " + problem);
  return true;
}

void lowerPluginPeriphery(CompileContext& ctx, const Component& c, const Built& parent) {
  const PluginType& t = *c.type->plugin;
  const std::string key = ctx.modelKey(c);
  const bool sensor = t.c->kind == SIMBOB_SENSOR;
  if (sensor)
    ctx.recordSensor(key, kFailedActuator);  // until it is lowered: controllers referring to it say nothing more
  else
    ctx.recordActuator(key, kFailedActuator);
  if (!parent.ok) return;
  Transform pose;
  if (!lowerSensorPose(ctx, c, c.get(kPose), parent, &pose)) return;
  if (sensor) {
    SensorDef s;
    s.key = key;
    s.loc = c.loc;
    s.kind = SensorKind::Plugin;
    s.body = parent.index;
    s.static_body = parent.static_id;
    s.pose = pose;
    s.period = c.get(kPeriod);
    if (!checkSensorPeriod(ctx, c, c.slotOf(kPeriod), s.period)) return;
    s.plugin = t.c;
    s.numbers = numbersOf(c, t);
    s.quantities = t.quantities;
    s.plugin_who = pluginWho(t.plugin, t.name);
    for (size_t i = 0; i < t.numbers.size(); ++i) {  // what RCObstacleAvoider reads of an RCRangeSensor
      if (t.numbers[i].name == "MinRange") s.min_range = s.numbers[i];
      if (t.numbers[i].name == "MaxRange") s.max_range = s.numbers[i];
    }
    ctx.recordSensor(key, static_cast<int>(ctx.model.sensors.size()));
    ctx.model.sensors.push_back(std::move(s));
    return;
  }
  ActuatorDef a;
  a.key = key;
  a.loc = c.loc;
  a.kind = ActuatorDef::Plugin;
  a.body = parent.index;
  a.static_body = parent.static_id;
  a.pose = pose;
  a.plugin = t.c;
  a.numbers = numbersOf(c, t);
  a.plugin_who = pluginWho(t.plugin, t.name);
  ctx.recordActuator(key, static_cast<int>(ctx.model.actuators.size()));
  ctx.model.actuators.push_back(std::move(a));
}

}  // namespace simbob
