// The inputs a command reads besides its scene: the global settings (--settings) and the scene
// overrides (--set, the shorthands, the DocumentIni's cameras).
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "cli.h"
#include "simbob/document_ini.h"
#include "simbob/frame_sinks.h"
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

void appendSceneInputs(const Scene& scene, const std::string& path, const std::vector<Override>& overrides,
                       std::vector<NamedPath>* inputs) {
  for (const std::string& f : scene.files) inputs->push_back({f == path ? "the scene" : "the import", f});
  for (const Override& o : overrides)
    if (o.line > 0) inputs->push_back({"the DocumentIni", o.place});
}

void appendModelInputs(const Model& model, const Common& common, const std::string& scene,
                       std::vector<NamedPath>* inputs) {
  // The renderer's lookup (lib/render/renderer.cpp loadTextures): every candidate that exists.
  for (const SkinDef& s : model.skins) {
    if (s.texture.empty()) continue;
    for (const std::string& dir : {common.texture_folder, s.base_dir}) {
      if (dir.empty()) continue;
      for (const char* ext : {"", ".bmp", ".png"}) {
        const std::string p = (s.texture[0] == '/' ? "" : dir + "/") + s.texture + ext;
        std::error_code ec;
        if (std::filesystem::is_regular_file(p, ec)) inputs->push_back({"the texture", p});
      }
    }
  }
  if (common.document_ini) inputs->push_back({"the DocumentIni", documentIniPath(scene)});
}

int checkRecordFolder(const std::string& dir, const std::vector<NamedPath>& outputs,
                      const std::vector<NamedPath>& inputs) {
  if (dir.empty()) return 0;
  auto inFolder = [&](const std::string& p) {
    if (p.empty() || p == "-" || isStreamOutput(p)) return false;
    const std::filesystem::path path(p);
    if (!isFrameFileName(path.filename().string())) return false;
    const std::string parent = path.has_parent_path() ? path.parent_path().string() : ".";
    return sameOutputPlace(parent, dir);
  };
  for (const auto* list : {&inputs, &outputs})
    for (const NamedPath& f : *list)
      if (inFolder(f.path)) {
        g_log.error({ErrorKind::InvalidInput,
                     {},
                     f.what + " " + quoteInput(f.path, 400) + " is a frame file of --record " + quoteInput(dir, 400) +
                         ", which the recording writes or removes: " +
                         (list == &inputs ? "an output must not overwrite an input"
                                          : "outputs of one command must not collide")});
        return kExitUsage;
      }
  return 0;
}

bool loadAndCompile(const std::string& path, const Registry& reg, Scene* scene, Model* model, int* code, bool warnings,
                    bool collect_all, const std::vector<NamedPath>& inputs, const std::vector<Override>& overrides) {
  Diagnostics d;
  const bool loaded = loadScene(path, reg, scene, d) && applyOverrides(*scene, overrides, d);
  // A scene that failed to load is still a consistent graph (bad links are empty), so `check`
  // compiles it too and reports what the compile step finds in the same pass.
  const bool ok = (loaded || (collect_all && !scene->comps.empty())) && compileScene(*scene, model, d) && loaded;
  std::vector<NamedPath> read = inputs;
  appendSceneInputs(*scene, path, overrides, &read);
  if (g_log.file) {
    if (int c = checkOutputs({{"--log-file", g_log.path}}, read)) {
      *code = c;
      return false;
    }
  }
  if (!ok) {
    *code = report(d, warnings);
    return false;
  }
  report(d, warnings);
  return true;
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
