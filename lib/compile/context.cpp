#include "compile/context.h"

namespace simbob {

std::string CompileContext::modelKey(const Component& c) const {
  std::string key = c.qkey;
  if (!clone.active) return key;
  // Innermost clone first: inside clone C2 of clone C1 of B, "B.x" -> "C1.x" -> "C2.x".
  for (auto r = clone.renames.rbegin(); r != clone.renames.rend(); ++r) {
    const std::string& from = r->first;
    if (key.compare(0, from.size(), from) == 0 && (key.size() == from.size() || key[from.size()] == '.'))
      key = r->second + key.substr(from.size());
  }
  return key;
}

int CompileContext::bodyIndex(const std::string& model_key) const { return body_index_.find(model_key); }

int CompileContext::jointIndex(const std::string& model_key) const { return joint_index_.find(model_key); }

}  // namespace simbob
