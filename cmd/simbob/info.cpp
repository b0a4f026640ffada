// simbob check, dump, types: loading, normalising and describing scenes.
#include <cstdio>

#include "cli.h"
#include "commands.h"
#include "simbob/compile.h"
#include "simbob/overrides.h"
#include "simbob/registry.h"
#include "simbob/simulation.h"
#include "simbob/values.h"
#include "simbob/tool/replay_page.h"

namespace simbob::cli {

int cmdCheck(const std::string& path, const Common& common, const std::vector<std::string>& sets, double dt) {
  std::vector<Override> overrides;
  if (int c = sceneOverrides(common, path, sets, &overrides)) return c;
  exitOnStopSignals(path, "loading");
  LoadReport loaded;
  Model model;
  int code = 0;
  if (!loadAndCompile(path, *common.registry, &model, &loaded, &code, true, true, {{"--settings", common.settings}},
                      overrides))
    return code;
  Diagnostics lint;
  lintModel(model, lint, dt);
  checkTextureBudgets(model, common.texture_folder, lint);
  checkMeshBudget(model, lint);
  size_t programs = 0;
  for (const SocketDef& d : model.sockets) {
    if (d.controller.empty()) continue;
    ++programs;
    if (common.no_controllers) {
      SimulationOptions so;
      so.no_controllers = true;
      Simulation::fromModel(model, so, lint);  // refuses it, with run's words
      break;
    }
    g_log.info(d.loc.file.str() + ":" + std::to_string(d.loc.line) + ": RCLocalSocketCommunicator '" + d.key +
               "' starts the program '" + quoteInput(d.controller, 400) + "' in " +
               quoteInput(controllerFolder(d), 400) +
               " when the scene runs (run, batch, sweep run, render --at, Python's Simulation)");
  }
  if (int c = report(lint, true)) return c;
  for (const ImportReport& r : model.imports) {  // what each URDF import built, ignored or approximated
    g_log.note({ErrorKind::InvalidInput, r.loc, r.text});
    for (const Error& n : r.notes) g_log.note(n);
  }
  g_log.info(path + ": ok (" + countOf(model.bodies.size(), "mobile body", "mobile bodies") + ", " +
             countOf(model.geoms.size(), "geom", "geoms") + ", " + countOf(model.joints.size(), "joint", "joints") +
             (programs ? "; starts " + countOf(programs, "program", "programs") : std::string()) + ")");
  for (const std::string& line : describeMeshes(model)) g_log.info(path + ": " + line);
  return kExitOk;
}

int cmdDump(const std::string& path, const std::string& format, const Common& common,
            const std::vector<std::string>& sets) {
  std::vector<Override> overrides;
  if (int c = sceneOverrides(common, path, sets, &overrides)) return c;
  exitOnStopSignals(path, "loading");
  Scene scene;
  Diagnostics d;
  const bool ok = loadScene(path, *common.registry, &scene, d) && applyOverrides(scene, overrides, d);
  std::vector<NamedPath> read = {{"--settings", common.settings}};
  LoadReport loaded;
  loaded.files = scene.files;
  appendSceneInputs(loaded, path, overrides, &read);
  if (int c = checkOutputs({{"--log-file", g_log.path}}, read)) return c;
  if (!ok) return report(d, true);
  std::string text = writeScene(scene, format == "ini" ? Format::Ini : Format::Xml, true);
  std::fwrite(text.data(), 1, text.size(), stdout);
  return std::fflush(stdout) == 0 ? kExitOk : kExitIoErr;
}

namespace {

std::string defaultText(const ParamSpec& p) {
  switch (p.kind) {
    case ParamKind::Value:
      return formatValue(p.type, p.default_value, p.table);
    case ParamKind::Component:
    case ParamKind::Struct:
      return p.default_type.empty() ? "(none)" : p.default_type;
    case ParamKind::List:
      return "(empty)";
  }
  return "";
}

std::string typeText(const ParamSpec& p) {
  switch (p.kind) {
    case ParamKind::Value: {
      std::string s = valueTypeName(p.type);
      if (p.table) {
        s += " (";
        for (size_t i = 0; i < p.table->keys.size(); ++i) s += (i ? "|" : "") + std::string(p.table->keys[i].name);
        s += ")";
      }
      return s;
    }
    case ParamKind::Component:
    case ParamKind::List: {
      std::string s = p.kind == ParamKind::List ? "List of " : "";
      for (size_t i = 0; i < p.families.size(); ++i) s += (i ? " | " : "") + std::string(familyName(p.families[i]));
      return s;
    }
    case ParamKind::Struct:
      return "Struct " + p.struct_type;
  }
  return "";
}

// A markdown table cell: '|' would end the cell (GitHub tables split on it even inside code
// spans), so it is escaped; enums ("Off|Linear") and family lists ("A | B") contain it.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

int cmdTypes(bool markdown, const Registry& reg, const std::string& only) {
  const TypeSpec* one = nullptr;
  if (!only.empty()) {
    one = reg.findIgnoreCase(only);
    if (!one) {
      g_log.error({ErrorKind::InvalidInput, {}, reg.unknownTypeMessage(only, false) + "; simbob types lists them all"});
      return kExitUsage;
    }
  }
  std::string out;
  if (markdown && !one)
    out += "# simbob component types\n\nGenerated by `simbob types --markdown` from the registry.\n";
  for (const TypeSpec& t : reg.types()) {
    if (one && &t != one) continue;
    std::string aliases;
    for (const auto& a : t.aliases) aliases += (aliases.empty() ? "" : ", ") + a;
    if (markdown) {
      out += "\n## " + t.name + " (" + familyName(t.family) + ")\n\n" + t.doc + "\n";
      if (!aliases.empty()) out += "\nAlso accepted as: " + aliases + ".\n";
      if (t.finished_here) out += "\n*Marked unfinished (\\*) in the original guide; finished in simbob.*\n";
      if (!t.params.empty()) {
        out += "\n| Parameter | Type | Default | Unit | Meaning |\n|---|---|---|---|---|\n";
        for (const auto& p : t.params)
          out += "| " + cell(p.name) + " | " + cell(typeText(p)) + " | `" + cell(defaultText(p)) + "` | " +
                 cell(p.unit) + " | " + cell(p.doc) + " |\n";
      }
      for (const auto& [name, advice] : t.retired) out += "\nRemoved: `" + name + "`: " + advice + ".\n";
    } else {
      out +=
          t.name + " (" + familyName(t.family) + (aliases.empty() ? "" : "; alias " + aliases) + "): " + t.doc + "\n";
      for (const auto& p : t.params)
        out += "  " + p.name + " : " + typeText(p) + " = " + defaultText(p) +
               (p.unit.empty() ? "" : " [" + p.unit + "]") + "  -- " + p.doc + "\n";
      for (const auto& [name, advice] : t.retired) out += "  " + name + " : removed -- " + advice + "\n";
    }
  }
  if (one) {
    // Its Macros, if any: they are ways to write it.
    std::string macros;
    for (const auto& m : reg.macros())
      if (m.type == one->name) macros += "  " + m.name + " -> " + m.type + ": " + m.doc + "\n";
    if (!macros.empty()) out += (markdown ? "\nMacros:\n\n" : "Macros:\n") + macros;
    std::fwrite(out.data(), 1, out.size(), stdout);
    return kExitOk;
  }
  out += markdown ? "\n## Macros\n\n| Macro | Creates | Meaning |\n|---|---|---|\n" : "\nMacros:\n";
  for (const auto& m : reg.macros()) {
    if (markdown)
      out += "| " + cell(m.name) + " | " + cell(m.type) + " | " + cell(m.doc) + " |\n";
    else
      out += "  " + m.name + " -> " + m.type + " (" + familyName(m.family) + "): " + m.doc + "\n";
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return kExitOk;
}

}  // namespace simbob::cli
