#include "simbob/error.h"

#include <mutex>
#include <unordered_set>

namespace simbob {

namespace {
// Node-based: the strings never move, so their addresses can be handed out.
struct NamePool {
  std::mutex mutex;
  std::unordered_set<std::string> names{std::string()};
};
NamePool& pool() {
  static NamePool* p = new NamePool;  // never destroyed: FileNames may be read during exit
  return *p;
}
}  // namespace

const std::string* FileName::empty_() {
  static const std::string* e = &*pool().names.find(std::string());
  return e;
}

const std::string* FileName::intern(const std::string& name) {
  if (name.empty()) return empty_();
  NamePool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  return &*p.names.insert(name).first;
}

std::string Error::str() const {
  if (loc.file.empty()) return message;
  std::string out = loc.file.str();
  if (loc.line > 0) {
    out += ':';
    out += std::to_string(loc.line);
  }
  out += ": ";
  out += message;
  return out;
}

}  // namespace simbob
