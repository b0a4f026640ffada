// INI format (guide 4.1) as a Source: case-insensitive dotted keys, sections as key prefixes,
// lists as NameCount + Name0.., components as X.Type / X.Key (and X.Ref / X.Macro).
#include <algorithm>
#include <cctype>
#include <unordered_map>
#include <unordered_set>

#include "scene/source.h"
#include "simbob/values.h"

namespace simbob {

struct IniNode {
  std::string name;   // as written
  std::string lname;  // lower case, for matching
  int line = 0;
  bool has_value = false;
  std::string value;
  std::vector<IniNode> children;                  // first-appearance order
  std::unordered_map<std::string, size_t> index;  // lname -> children[i]; lookup only, never iterated

  IniNode* child(const std::string& lower) {
    auto it = index.find(lower);
    return it == index.end() ? nullptr : &children[it->second];
  }
  IniNode* add(IniNode n) {
    index.emplace(n.lname, children.size());
    children.push_back(std::move(n));
    return &children.back();
  }
};

struct IniDoc {
  IniNode root;
};

namespace {

// INI lists are read item by item; a count beyond this is a typo or an attack, not a scene.
constexpr int64_t kMaxListCount = 10000000;

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

class IniSource : public Source {
 public:
  IniSource(IniNode* node, std::vector<std::string> pre_read) : node_(node), read_(pre_read.begin(), pre_read.end()) {}

  int line() const override { return node_->line; }
  bool ignoresCase() const override { return true; }

  SourceValue value(const std::string& name) override {
    SourceValue v;
    IniNode* c = take(name);
    if (!c) return v;
    v.present = true;
    v.line = c->line;
    if (!c->has_value || !c->children.empty())
      v.error = "parameter '" + name + "' is a value: write '" + name + " = ...'";
    v.text = c->value;
    return v;
  }

  SourceLink component(const std::string& name) override {
    IniNode* c = take(name);
    if (!c) return {};
    return linkFrom(c, name);
  }

  std::vector<SourceLink> list(const std::string& name, bool* present, int* line) override {
    std::vector<SourceLink> items;
    const std::string base = listItemName(name);
    IniNode* count = take(base + "Count");
    *present = count != nullptr;
    if (!count) return missingCount(base, present, line);
    *line = count->line;
    auto n = parseNumber(trim(count->value));
    // Range first: casting a double beyond int64 to int64 is undefined behaviour.
    if (!count->has_value || !n || *n < 0 || *n > kMaxListCount ||
        *n != static_cast<double>(static_cast<int64_t>(*n))) {
      SourceLink bad;
      bad.present = true;
      bad.line = count->line;
      if (count->has_value && n && *n > kMaxListCount)
        bad.error = base + "Count " + quoteInput(count->value) + " is beyond the limit of " +
                    std::to_string(kMaxListCount) + " items";
      else
        bad.error = base + "Count must be a whole number >= 0, got '" + quoteInput(count->value) + "'";
      items.push_back(std::move(bad));
      return items;
    }
    for (int64_t i = 0; i < static_cast<int64_t>(*n); ++i) {
      std::string item = base + std::to_string(i);
      IniNode* c = take(item);
      if (!c) {
        // One message for the first gap: a wrong count must not produce millions of errors.
        SourceLink missing;
        missing.present = true;
        missing.line = count->line;
        missing.error = base + "Count is " + quoteInput(count->value) + " but " + item + " is missing";
        items.push_back(std::move(missing));
        break;
      }
      items.push_back(linkFrom(c, item));
    }
    return items;
  }

  std::unique_ptr<Source> structure(const std::string& name, int* line) override {
    IniNode* c = take(name);
    if (!c) return nullptr;
    *line = c->line;
    return std::make_unique<IniSource>(c, std::vector<std::string>{});
  }

  std::vector<std::pair<std::string, int>> unread() const override {
    std::vector<std::pair<std::string, int>> out;
    for (const auto& c : node_->children)
      if (!read_.count(c.lname)) out.emplace_back(c.name, c.line);
    return out;
  }

 private:
  /// Items Name0, Name1, ... written without NameCount: one error that says the count is
  /// missing (else each item would be reported as an unknown parameter).
  std::vector<SourceLink> missingCount(const std::string& base, bool* present, int* line) {
    std::vector<SourceLink> items;
    IniNode* first = take(base + "0");
    if (!first) return items;
    int64_t n = 1;
    while (take(base + std::to_string(n))) ++n;
    *present = true;
    *line = first->line;
    SourceLink missing;
    missing.present = true;
    missing.line = first->line;
    missing.error = base + "Count is missing: " +
                    (n == 1 ? base + "0 needs" : base + "0 to " + base + std::to_string(n - 1) + " need") + " '" +
                    base + "Count = " + std::to_string(n) + "'";
    items.push_back(std::move(missing));
    return items;
  }

  IniNode* take(const std::string& name) {
    std::string ln = lower(name);
    IniNode* c = node_->child(ln);
    if (c && read_.insert(ln).second) return c;
    return nullptr;
  }

  SourceLink linkFrom(IniNode* c, const std::string& name) {
    SourceLink l;
    l.present = true;
    l.line = c->line;
    if (c->has_value) {
      l.error = "'" + name + "' is a component: write " + name + ".Type = ..., " + name + ".Ref = ... or " + name +
                ".Macro = ...";
      return l;
    }
    IniNode* type = c->child("type");
    IniNode* key = c->child("key");
    IniNode* ref = c->child("ref");
    IniNode* macro = c->child("macro");
    if (ref) l.ref = ref->value;
    if (macro) l.macro = macro->value;
    if (type) {
      l.type = type->value;
      l.line = type->line;
    }
    if (key) {
      l.key = key->value;
      l.has_key = true;
    }
    int kinds = (type ? 1 : 0) + (ref ? 1 : 0) + (macro ? 1 : 0);
    if (kinds != 1) {
      l.error = "'" + name + "' needs exactly one of " + name + ".Type, " + name + ".Ref, " + name + ".Macro";
      return l;
    }
    if ((ref && ref->value.empty())) l.error = "'" + name + "': empty Ref";
    if (type) {
      l.body = std::make_unique<IniSource>(c, std::vector<std::string>{"type", "key"});
    } else if (c->children.size() > 1) {
      l.error = "'" + name + "' with Ref or Macro takes no other entries";
    }
    return l;
  }

  IniNode* node_;
  std::unordered_set<std::string> read_;  // membership only, never iterated
};

}  // namespace

bool scanIni(const std::string& text, const IniEntryFn& entry, std::string* error, int* error_line) {
  // A NUL byte is no text: the XML writer (C strings) would silently cut the value there.
  if (size_t nul = text.find('\0'); nul != std::string::npos) {
    *error = "NUL byte in INI text";
    *error_line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n')) + 1;
    return false;
  }
  std::string section;
  // A UTF-8 byte order mark (Windows editors write one) is no part of the first key.
  size_t pos = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  int line_no = 0;
  auto failAt = [&](std::string message) {
    *error = std::move(message);
    *error_line = line_no;
    return false;
  };
  while (pos <= text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string_view line = trim(std::string_view(text).substr(pos, end - pos));
    ++line_no;
    pos = end + 1;
    if (line.empty() || line.front() == ';' || line.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    if (line.front() == '[') {
      if (line.back() != ']') return failAt("malformed section header '" + quoteInput(line) + "'");
      // "[]" (or "[ ]") returns to the global section: the keys below have no prefix.
      section = std::string(trim(line.substr(1, line.size() - 2)));
      if (end == text.size()) break;
      continue;
    }
    size_t eq = line.find('=');
    if (eq == std::string_view::npos) return failAt("expected 'key = value', got '" + quoteInput(line) + "'");
    std::string key(trim(line.substr(0, eq)));
    std::string_view value = trim(line.substr(eq + 1));
    if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
    if (key.empty()) return failAt("empty key before '='");
    std::string message;
    if (!entry(section.empty() ? key : section + "." + key, value, line_no, &message)) return failAt(message);
    if (end == text.size()) break;
  }
  return true;
}

std::shared_ptr<IniDoc> parseIni(const std::string& text, std::string* error, int* error_line) {
  auto doc = std::make_shared<IniDoc>();
  doc->root.line = 1;
  auto entry = [&](const std::string& full, std::string_view value, int line_no, std::string* message) {
    IniNode* node = &doc->root;
    size_t start = 0;
    while (true) {
      size_t dot = full.find('.', start);
      std::string part = full.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (part.empty()) {
        *message = "empty name in key '" + quoteInput(full) + "'";
        return false;
      }
      std::string lp = lower(part);
      IniNode* next = node->child(lp);
      if (!next) {
        IniNode fresh;
        fresh.name = part;
        fresh.lname = lp;
        fresh.line = line_no;
        next = node->add(std::move(fresh));
      }
      node = next;
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    if (node->has_value) {
      *message = "key '" + quoteInput(full) + "' assigned twice (first on line " + std::to_string(node->line) + ")";
      return false;
    }
    node->has_value = true;
    node->value = std::string(value);
    node->line = line_no;
    return true;
  };
  if (!scanIni(text, entry, error, error_line)) return nullptr;
  return doc;
}

std::unique_ptr<Source> iniRoot(const std::shared_ptr<IniDoc>& doc) {
  // The IniSource points into doc; the caller keeps doc alive while reading.
  return std::make_unique<IniSource>(&doc->root, std::vector<std::string>{});
}

}  // namespace simbob
