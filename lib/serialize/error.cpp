#include "simbob/error.h"

namespace simbob {

std::string Error::str() const {
  if (loc.file.empty()) return message;
  std::string out = loc.file;
  if (loc.line > 0) {
    out += ':';
    out += std::to_string(loc.line);
  }
  out += ": ";
  out += message;
  return out;
}

}  // namespace simbob
