// The inputs a command reads besides its scene: the global settings (--settings) and the scene
// overrides (--set, the shorthands, the DocumentIni's cameras).
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "cli.h"
#include "simbob/tool/document_ini.h"
#include "simbob/renderer.h"
#include "simbob/registry.h"
#include "simbob/values.h"

namespace simbob::cli {

int readSettings(Common& c) {
  if (c.settings.empty()) return 0;
  GlobalSettings g;
  Diagnostics d;
  if (!readGlobalSettings(c.settings, *c.registry, &g, d)) return report(d, true);
  const std::string& log = g.log_file;
  if (c.log_file.empty() && !log.empty()) c.log_file = log;
  // ExtensionFolder is relative to the settings file's folder.
  c.extension_folder = g.extension_folder;
  if (!c.extension_folder.empty() && std::filesystem::path(c.extension_folder).is_relative())
    c.extension_folder = (std::filesystem::path(c.settings).parent_path() / c.extension_folder).string();
  c.document_ini = g.document_ini;
  const std::string& tex = g.texture_folder;
  if (!tex.empty()) {
    const size_t slash = c.settings.find_last_of('/');
    c.texture_folder = tex[0] == '/' || slash == std::string::npos ? tex : c.settings.substr(0, slash + 1) + tex;
  }
  return 0;
}

void appendSceneInputs(const LoadReport& loaded, const std::string& path, const std::vector<Override>& overrides,
                       std::vector<NamedPath>* inputs) {
  for (const std::string& f : loaded.files) inputs->push_back({f == path ? "the scene" : "the import", f});
  for (const Override& o : overrides)
    if (o.line > 0) inputs->push_back({"the DocumentIni", o.place});
}

void appendModelInputs(const Model& model, const Common& common, const std::string& scene,
                       std::vector<NamedPath>* inputs) {
  for (const std::string& t : textureFiles(model, common.texture_folder)) inputs->push_back({"the texture", t});
  if (common.document_ini) inputs->push_back({"the DocumentIni", documentIniPath(scene)});
}

bool loadAndCompile(const std::string& path, const Registry& reg, Model* model, LoadReport* loaded, int* code,
                    bool warnings, bool collect_all, const std::vector<NamedPath>& inputs,
                    const std::vector<Override>& overrides) {
  LoadRequest req;
  req.path = path;
  req.overrides = overrides;
  req.collect_all = collect_all;
  const bool ok = loadModel(req, reg, model, loaded);
  std::vector<NamedPath> read = inputs;
  appendSceneInputs(*loaded, path, overrides, &read);
  if (g_log.file) {
    if (int c = checkOutputs({{"--log-file", g_log.path}}, read)) {
      *code = c;
      return false;
    }
  }
  *code = report(loaded->diagnostics, warnings);
  return ok;
}

int parseSetOptions(const std::vector<std::string>& sets, std::vector<Override>* out) {
  for (const std::string& text : sets) {
    Override o;
    std::string err;
    if (!parseOverride(text, &o, &err)) {
      g_log.error({ErrorKind::InvalidInput, {"--set " + quoteInput(text), 0}, err});
      return kExitUsage;
    }
    out->push_back(std::move(o));
  }
  return kExitOk;
}

int sceneOverrides(const Common& c, const std::string& scene, const std::vector<std::string>& sets,
                   std::vector<Override>* out) {
  if (c.document_ini) {
    Diagnostics d;
    if (!readDocumentIni(documentIniPath(scene), out, d)) return report(d, true);
  }
  return parseSetOptions(sets, out);
}

}  // namespace simbob::cli
