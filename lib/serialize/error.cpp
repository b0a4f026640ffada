#include "simbob/error.h"

#include <cstdint>
#include <cstdio>
#include <mutex>
#include <unordered_set>

namespace simbob {

namespace {
// Node-based: the strings never move, so their addresses can be handed out.
struct NamePool {
  std::mutex mutex;
  std::unordered_set<std::string> names;
};
NamePool& pool() {
  static NamePool* p = new NamePool;  // never destroyed: FileNames may be read during exit
  return *p;
}
}  // namespace

const std::string& FileName::emptyName() {
  static const std::string* e = new std::string();  // never destroyed, as the pool
  return *e;
}

const std::string* FileName::intern(const std::string& name) {
  if (name.empty()) return nullptr;
  NamePool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  return &*p.names.insert(name).first;
}

namespace {

// Code points that print as nothing (or reorder the text around them): shown escaped.
bool invisible(uint32_t cp) {
  return cp == 0xAD || (cp >= 0x80 && cp < 0xA0) || (cp >= 0x200B && cp <= 0x200F) || (cp >= 0x2028 && cp <= 0x202E) ||
         (cp >= 0x2060 && cp <= 0x2064) || (cp >= 0x2066 && cp <= 0x206F) || cp == 0xFEFF ||
         (cp >= 0xFFF9 && cp <= 0xFFFB);
}

// Length of the UTF-8 sequence at s[i] and its code point; 0 if invalid.
size_t utf8At(std::string_view s, size_t i, uint32_t* cp) {
  const auto c = static_cast<unsigned char>(s[i]);
  size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  uint32_t v = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
  for (size_t k = 1; k < n; ++k) {
    const auto cc = static_cast<unsigned char>(s[i + k]);
    if ((cc >> 6) != 0x2) return 0;
    v = (v << 6) | (cc & 0x3F);
  }
  static const uint32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
  if (v < kMin[n] || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 0;
  *cp = v;
  return n;
}

}  // namespace

std::string quoteInput(std::string_view text, size_t max_bytes) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    if (out.size() >= max_bytes) {
      out += "... (" + std::to_string(text.size()) + " bytes)";
      return out;
    }
    uint32_t cp = 0;
    const size_t n = utf8At(text, i, &cp);
    if (n == 0 || cp < 0x20 || cp == 0x7F) {
      const auto c = static_cast<unsigned char>(text[i]);
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
      ++i;
    } else if (invisible(cp)) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "\\u{%04X}", static_cast<unsigned>(cp));
      out += buf;
      i += n;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
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

std::string Error::errorLine() const {
  std::string where = "simbob";
  if (!loc.file.empty()) where = loc.line > 0 ? loc.file.str() + ":" + std::to_string(loc.line) : loc.file.str();
  return where + ": error: " + message;
}

}  // namespace simbob
