// DocumentIni (guide 3.3.1): the camera settings beside a scene, read as overrides. The guide's
// GUI also wrote the file back when a simulation closed (the user had moved the camera with the
// mouse); a batch run moves no camera, so simbob only reads it.
#include "simbob/tool/document_ini.h"

#include <sys/stat.h>

#include <cerrno>
#include <string_view>

#include "scene/source.h"
#include "simbob/tool/files.h"
#include "simbob/values.h"

namespace simbob {

std::string documentIniPath(const std::string& scene_path) {
  const size_t slash = scene_path.find_last_of('/');
  const size_t dot = scene_path.find_last_of('.');
  const size_t name = slash == std::string::npos ? 0 : slash + 1;
  // A leading dot (".hidden") starts a name, not an extension.
  const bool has_ext = dot != std::string::npos && dot > name;
  std::string ini = (has_ext ? scene_path.substr(0, dot) : scene_path) + ".ini";
  return ini == scene_path ? std::string() : ini;
}

bool readDocumentIni(const std::string& path, std::vector<Override>* out, Diagnostics& diag) {
  struct stat st {};
  if (path.empty() || (::stat(path.c_str(), &st) != 0 && errno == ENOENT)) return true;
  std::string text, err;
  if (!readFile(path, kMaxSceneFileBytes, &text, &err, true)) {
    diag.error({path, 0}, "cannot read the DocumentIni: " + err, ErrorKind::MissingInput);
    return false;
  }
  auto entry = [&](const std::string& key, std::string_view value, int line, std::string* message) {
    Override o;
    if (!parseOverride(key + "=" + std::string(value), &o, message)) {
      *message = "expected 'CAMERA.PARAM = VALUE' or 'PARAM = VALUE' under [CAMERA], got '" + quoteInput(key) + "'";
      return false;
    }
    o.place = path;
    o.line = line;
    o.cameras_only = true;
    out->push_back(std::move(o));
    return true;
  };
  int line = 0;
  if (!scanIni(text, entry, &err, &line)) {
    diag.error({path, line}, err);
    return false;
  }
  return true;
}

}  // namespace simbob
