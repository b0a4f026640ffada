// A format-neutral view of a component's parameters in a source file, so that one builder,
// driven by the registry's parameter tables, reads both XML (4.2) and INI (4.1).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "simbob/error.h"

namespace simbob {

class Source;

/// Items and count of a list parameter take its name without "List" (guide 4.1:
/// "StructList" -> "StructCount", "Struct0"; "ComponentList" -> "Component").
inline std::string listItemName(const std::string& list_name) {
  const std::string suffix = "List";
  if (list_name.size() > suffix.size() &&
      list_name.compare(list_name.size() - suffix.size(), suffix.size(), suffix) == 0)
    return list_name.substr(0, list_name.size() - suffix.size());
  return list_name;
}

/// What a component-valued entry says: an inline type element, a Ref, or a Macro. The texts are
/// views into the document, which outlives the Sources and links read from it: no string is
/// made for every entry of a large scene.
struct SourceLink {
  bool present = false;
  int line = 0;
  std::string_view type;  ///< inline component's type name
  std::string_view key;
  bool has_key = false;
  std::string_view ref;
  std::string_view macro;
  std::unique_ptr<Source> body;  ///< inline component's parameters
  std::string error;             ///< malformed entry (e.g. two type elements)
  const void* entry = nullptr;   ///< where the entry is in its document, for Source::forget
};

struct SourceValue {
  bool present = false;
  int line = 0;
  std::string_view text;  ///< into the document, which outlives the Source (no copy per value)
  std::string error;      ///< e.g. element without Value attribute
};

/// Parameters of one component or struct in a file. Each accessor marks what it read, so that
/// unread entries can be reported as unknown parameters.
class Source {
 public:
  virtual ~Source() = default;
  virtual int line() const = 0;
  virtual SourceValue value(const std::string& name) = 0;
  virtual SourceLink component(const std::string& name) = 0;
  /// Items of a list parameter; `present` tells whether the list was written at all.
  virtual std::vector<SourceLink> list(const std::string& name, bool* present, int* line) = 0;
  virtual std::unique_ptr<Source> structure(const std::string& name, int* line) = 0;
  /// Entries never read: (name, line).
  virtual std::vector<std::pair<std::string, int>> unread() const = 0;
  /// Whether parameter names match case-insensitively (INI) or exactly (XML).
  virtual bool ignoresCase() const = 0;
  /// The builder is done with list item `item` (one of list()'s, with its body gone): the source
  /// may free what it holds of it. The XML source drops the item's elements, so that a large
  /// scene's document shrinks while its graph grows instead of both peaking together. The
  /// texts of the item's views stay valid (they are in the document's text).
  virtual void forget(const SourceLink& item) { (void)item; }
};

class Registry;

/// Parse XML text; the registry tells type elements from wrapper elements in lists. The document
/// keeps `text` and is parsed in place (no second copy of a large scene). `reread` gives the
/// text again, as it was, for the message about an element left open (in-place parsing changes
/// it); without it that message names only the line.
struct XmlDoc;
std::shared_ptr<XmlDoc> parseXml(std::string text, const Registry& reg, std::string* error, int* error_line,
                                 const std::function<std::string()>& reread = {});
std::unique_ptr<Source> xmlRoot(const std::shared_ptr<XmlDoc>& doc, std::string* root_name);
/// The document node itself, whose one parameter is the root element: imports read
/// component("Body") / component("Joint") / list("RefList") from it.
std::unique_ptr<Source> xmlDocument(const std::shared_ptr<XmlDoc>& doc);

/// One `key = value` line of an INI text: the key with its section as prefix ("[A] b = 1" gives
/// "A.b"), the value trimmed and unquoted, the line number. Returns false with a message to stop.
using IniEntryFn = std::function<bool(const std::string& key, std::string_view value, int line, std::string* message)>;
/// The INI syntax of guide 4.1, line by line: comments (';', '#'), [sections], key = value.
/// Returns false with the message and line of the first malformed line or refused entry.
bool scanIni(const std::string& text, const IniEntryFn& entry, std::string* error, int* error_line);

struct IniDoc;
std::shared_ptr<IniDoc> parseIni(const std::string& text, std::string* error, int* error_line);
std::unique_ptr<Source> iniRoot(const std::shared_ptr<IniDoc>& doc);

}  // namespace simbob
