// XML format (guide 4.2) as a Source: <Name Value=".."/>, type elements with Key, Ref, Macro.
#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <set>
#include <string_view>
#include <pugixml.hpp>

#include "scene/source.h"
#include "simbob/registry.h"

namespace simbob {

struct XmlDoc {
  pugi::xml_document doc;
  std::string text;
  std::vector<size_t> newlines;  // offsets of '\n', for offset -> line
  const Registry* reg = nullptr;

  // Sources ask for lines in about document order: look a few lines on from the last answer
  // before searching them all (a binary search over 50,000 lines for each element otherwise).
  int lineOf(const pugi::xml_node& n) const {
    // An element's name lies in the text parsed in place: its place there is its offset (what
    // offset_debug() works out for any node, at several times the cost).
    const char* name = n.name();
    const auto off = name >= text.data() && name < text.data() + text.size() ? static_cast<size_t>(name - text.data())
                                                                             : static_cast<size_t>(n.offset_debug());
    size_t i = hint_;
    if (i > 0 && newlines[i - 1] > off) i = 0;  // behind the last answer: search from the top
    for (int step = 0; step < kLookAhead && i < newlines.size() && newlines[i] <= off; ++step) ++i;
    if (i < newlines.size() && newlines[i] <= off)
      i = static_cast<size_t>(std::upper_bound(newlines.begin() + static_cast<ptrdiff_t>(i), newlines.end(), off) -
                              newlines.begin());
    hint_ = i;
    return static_cast<int>(i) + 1;
  }

 private:
  static constexpr int kLookAhead = 8;
  mutable size_t hint_ = 0;  // lines before the last offset asked about
};

namespace {

bool isElement(const pugi::xml_node& n) { return n.type() == pugi::node_element; }

// An attribute that is one of `known` in another case ("value" for "Value") gets a message
// that says so; others are unknown.
std::string attributeError(const std::string& where, const std::string& an, std::initializer_list<const char*> known) {
  for (const char* k : known)
    if (equalsIgnoreCase(an, k))
      return where + ": attribute '" + an + "' must be written '" + k + "' (XML names are case-sensitive)";
  return where + ": unknown attribute '" + an + "'";
}

// Attributes are walked with first_attribute()/next_attribute(): pugixml's attribute ranges
// cost four calls into the library per attribute, for every element of a large scene.
class XmlSource : public Source {
 public:
  XmlSource(std::shared_ptr<XmlDoc> doc, pugi::xml_node node) : doc_(std::move(doc)), node_(node) {}

  // A source lives while its component is built: a few at a time, one made and dropped for
  // every component of a large scene. Their memory is kept for the next on the same thread.
  static void* operator new(size_t size) {
    std::vector<void*>& kept = spare();
    if (size != sizeof(XmlSource) || kept.empty()) return ::operator new(size);
    void* p = kept.back();
    kept.pop_back();
    return p;
  }
  static void operator delete(void* p, size_t size) {
    std::vector<void*>& kept = spare();
    if (size != sizeof(XmlSource) || kept.size() >= kMaxSpare) return ::operator delete(p);
    kept.push_back(p);
  }

  int line() const override { return doc_->lineOf(node_); }
  bool ignoresCase() const override { return false; }

  SourceValue value(const std::string& name) override {
    SourceValue v;
    pugi::xml_node c = take(name);
    if (!c) return v;
    v.present = true;
    v.line = doc_->lineOf(c);
    // One walk over the attributes: the (first) Value attribute, the first other one that is
    // "Value" in another case, and the last other one, whose message stands otherwise.
    pugi::xml_attribute a;
    const char* miscased = nullptr;
    const char* other = nullptr;
    for (pugi::xml_attribute at = c.first_attribute(); at; at = at.next_attribute()) {
      const char* an = at.name();
      if (std::strcmp(an, "Value") == 0) {
        if (!a) a = at;
        continue;
      }
      if (!miscased && equalsIgnoreCase(an, "Value")) miscased = an;
      other = an;
    }
    if (!a && miscased) {  // <Height value="3"/>: the case is wrong
      v.error = attributeError("parameter '" + name + "'", miscased, {"Value"});
      return v;
    }
    if (other) v.error = attributeError("parameter '" + name + "'", other, {"Value"});
    if (!a) {
      v.error = "parameter '" + name + "' needs a Value attribute";
      return v;
    }
    v.text = a.value();
    if (v.error.empty() && firstElement(c)) v.error = "parameter '" + name + "' is a value and takes no child elements";
    return v;
  }

  SourceLink component(const std::string& name) override {
    pugi::xml_node c = take(name);
    if (!c) return {};
    return linkFrom(c, true);
  }

  void forget(const SourceLink& item) override {
    if (!item.entry) return;
    pugi::xml_node n(static_cast<pugi::xml_node_struct*>(const_cast<void*>(item.entry)));
    n.parent().remove_child(n);
  }

  std::vector<SourceLink> list(const std::string& name, bool* present, int* line) override {
    std::vector<SourceLink> items;
    pugi::xml_node c = take(name);
    *present = bool(c);
    if (!c) return items;
    *line = doc_->lineOf(c);
    for (pugi::xml_node item : c.children()) {
      if (!isElement(item)) continue;
      if (doc_->reg->find(item.name())) {
        items.push_back(typeElement(item));
      } else if (!isWrapper(item)) {
        // Not a wrapper: a misspelled type element such as
        // <RCMobileRigidBodyy Key=".."><Geom>..</Geom></RCMobileRigidBodyy>.
        // The loader names it as an unknown type, with the nearest type names.
        SourceLink l;
        l.present = true;
        l.line = doc_->lineOf(item);
        l.type = item.name();
        items.push_back(std::move(l));
      } else {
        items.push_back(linkFrom(item, false));
      }
      items.back().entry = item.internal_object();
    }
    return items;
  }

  std::unique_ptr<Source> structure(const std::string& name, int* line) override {
    pugi::xml_node c = take(name);
    if (!c) return nullptr;
    *line = doc_->lineOf(c);
    return std::make_unique<XmlSource>(doc_, c);
  }

  std::vector<std::pair<std::string, int>> unread() const override {
    std::vector<std::pair<std::string, int>> out;
    for (const Child& k : children())
      if (!k.read) out.emplace_back(pugi::xml_node(k.node).name(), doc_->lineOf(pugi::xml_node(k.node)));
    return out;
  }

  SourceLink typeElement(pugi::xml_node t) {
    SourceLink l;
    l.present = true;
    l.line = doc_->lineOf(t);
    l.type = t.name();
    for (pugi::xml_attribute a = t.first_attribute(); a; a = a.next_attribute()) {
      const char* an = a.name();
      if (std::strcmp(an, "Key") == 0) {
        l.key = a.value();
        l.has_key = true;
      } else {
        l.error = attributeError(t.name(), an, {"Key"});
        if (!equalsIgnoreCase(an, "Key")) l.error += " (a type element takes only Key)";
      }
    }
    l.body = std::make_unique<XmlSource>(doc_, t);
    return l;
  }

 private:
  // A list item that is not a type element stands for a component only through a Ref or Macro
  // attribute or a single type element inside it. Anything else that carries a Key, or holds
  // no type element at all, is taken for a misspelled type element.
  bool isWrapper(pugi::xml_node n) const {
    if (n.attribute("Ref") || n.attribute("Macro")) return true;
    int kids = 0, types = 0;
    for (pugi::xml_node k : n.children()) {
      if (!isElement(k)) continue;
      ++kids;
      if (doc_->reg->find(k.name())) ++types;
    }
    if (kids == 1 && types == 1) return true;
    // <Component><RCMobilRigidBody/></Component>: a wrapper around a misspelled type element.
    if (kids == 1 && !n.attribute("Key") && doc_->reg->suggestType(n.name()).empty() &&
        !doc_->reg->suggestType(firstElement(n).name()).empty())
      return true;
    return !n.attribute("Key") && types > 0;
  }

  static pugi::xml_node firstElement(pugi::xml_node n) {
    for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling())
      if (isElement(c)) return c;
    return {};
  }

  // The first not-yet-read child element called `name`; a second one stays unread and is
  // reported as a duplicate by the builder. The builder asks for every parameter of the type,
  // most of them absent: the children's names are hashed once, and each question compares
  // hashes before names.
  pugi::xml_node take(const std::string& name) {
    const uint32_t h = nameHash(name.data(), name.size());
    for (Child& k : children()) {
      if (k.read || k.hash != h) continue;
      const pugi::xml_node c(k.node);
      if (std::strcmp(c.name(), name.c_str()) != 0) continue;
      k.read = true;
      return c;
    }
    return {};
  }

  struct Child {
    pugi::xml_node_struct* node;
    uint32_t hash;
    bool read;  ///< taken by a parameter
  };

  // A parameter's name by its length and three of its letters: names that share them cost a
  // strcmp more, and hashing every letter of every name asked for cost more than that.
  static uint32_t nameHash(const char* s, size_t n) {
    if (n == 0) return 0;
    const auto at = [s](size_t i) { return static_cast<uint32_t>(static_cast<unsigned char>(s[i])); };
    return static_cast<uint32_t>(n & 0xff) | at(0) << 8 | at(n / 2) << 16 | at(n - 1) << 24;
  }

  // The child elements, listed on the first question. Most elements have a few: those stay in
  // the Source itself, so that listing them allocates nothing (a vector grown child by child
  // cost two or three allocations for every component of a large scene).
  struct Children {
    Child* first;
    Child* last;
    Child* begin() const { return first; }
    Child* end() const { return last; }
  };
  Children children() const {
    if (!listed_) {
      listed_ = true;
      for (pugi::xml_node c = node_.first_child(); c; c = c.next_sibling()) {
        if (!isElement(c)) continue;
        const Child k{c.internal_object(), nameHash(c.name(), std::strlen(c.name())), false};
        if (count_ < kInlineChildren) {
          inline_[count_++] = k;
          continue;
        }
        if (more_.empty()) more_.assign(inline_.begin(), inline_.end());
        more_.push_back(k);
      }
    }
    if (!more_.empty()) return {more_.data(), more_.data() + more_.size()};
    return {inline_.data(), inline_.data() + count_};
  }

  // An element standing for a component: Ref or Macro attribute, or exactly one type element.
  SourceLink linkFrom(pugi::xml_node c, bool is_param) {
    SourceLink l;
    l.present = true;
    l.line = doc_->lineOf(c);
    for (pugi::xml_attribute a = c.first_attribute(); a; a = a.next_attribute()) {
      const char* an = a.name();
      if (std::strcmp(an, "Ref") == 0)
        l.ref = a.value();
      else if (std::strcmp(an, "Macro") == 0)
        l.macro = a.value();
      else
        l.error = attributeError(std::string("<") + c.name() + ">", an, {"Ref", "Macro"});
    }
    size_t kids = 0;  // child elements; the first is the component's type element
    pugi::xml_node first;
    for (pugi::xml_node k = c.first_child(); k; k = k.next_sibling())
      if (isElement(k) && kids++ == 0) first = k;
    if (!l.error.empty()) return l;
    if (!l.ref.empty() || !l.macro.empty()) {
      if (!l.ref.empty() && !l.macro.empty())
        l.error = std::string("<") + c.name() + "> has both Ref and Macro";
      else if (kids > 0)
        l.error = std::string("<") + c.name() + "> with Ref or Macro takes no child elements";
      else if (c.attribute("Ref") && l.ref.empty())
        l.error = std::string("<") + c.name() + ">: empty Ref";
      return l;
    }
    if (c.attribute("Ref")) {
      l.error = std::string("<") + c.name() + ">: empty Ref";
      return l;
    }
    if (kids != 1) {
      if (kids == 0 && !is_param)
        l.type = c.name();  // a misspelt type element; the loader names it
      else
        l.error = std::string("<") + c.name() + "> must hold exactly one component element, a Ref or a Macro";
      return l;
    }
    // An unknown type is named by the loader, with the nearest type names.
    return typeElement(first);
  }

  // The memory of sources dropped on this thread, ready for the next (freed when it ends).
  static constexpr size_t kMaxSpare = 256;
  static std::vector<void*>& spare() {
    struct Spare {
      std::vector<void*> blocks;
      ~Spare() {
        for (void* p : blocks) ::operator delete(p);
      }
    };
    thread_local Spare kept;
    return kept.blocks;
  }

  std::shared_ptr<XmlDoc> doc_;
  pugi::xml_node node_;
  static constexpr size_t kInlineChildren = 6;
  mutable bool listed_ = false;
  // Child elements in order, and which were read: in inline_ up to kInlineChildren, all of them
  // in more_ beyond.
  mutable size_t count_ = 0;
  mutable std::array<Child, kInlineChildren> inline_{};
  mutable std::vector<Child> more_;
};

// The element left open where a closing tag does not match (or the text ends): the stack of
// open tags up to byte `stop`, skipping comments, processing instructions, CDATA, DOCTYPE and
// quoted attribute values. Returns the open element's name and the offset of its '<', and in
// *closing the name of the closing tag found at `stop` ("" at the end of the text).
bool unclosedElement(std::string_view text, size_t stop, std::string* name, size_t* open_at, std::string* closing) {
  std::vector<std::pair<std::string_view, size_t>> open;
  auto skipTo = [&](size_t from, std::string_view end) {
    const size_t at = text.find(end, from);
    return at == std::string_view::npos ? text.size() : at + end.size();
  };
  auto nameAt = [&](size_t from) {
    size_t e = from;
    while (e < text.size() && !std::isspace(static_cast<unsigned char>(text[e])) && text[e] != '>' && text[e] != '/')
      ++e;
    return text.substr(from, e - from);
  };
  size_t i = 0;
  while ((i = text.find('<', i)) != std::string_view::npos && i < text.size()) {
    const std::string_view rest = text.substr(i);
    if (rest.compare(0, 4, "<!--") == 0) {
      i = skipTo(i + 4, "-->");
    } else if (rest.compare(0, 9, "<![CDATA[") == 0) {
      i = skipTo(i + 9, "]]>");
    } else if (rest.compare(0, 2, "<?") == 0) {
      i = skipTo(i + 2, "?>");
    } else if (rest.compare(0, 2, "<!") == 0) {
      i = skipTo(i + 2, ">");
    } else if (rest.compare(0, 2, "</") == 0) {
      const std::string_view n = nameAt(i + 2);
      if (open.empty()) return false;
      if (n != open.back().first || i >= stop) {
        *name = std::string(open.back().first);
        *open_at = open.back().second;
        *closing = std::string(n);
        return true;
      }
      open.pop_back();
      i = skipTo(i + 2, ">");
    } else {
      const std::string_view n = nameAt(i + 1);
      size_t j = i + 1 + n.size();
      char quote = 0;
      for (; j < text.size(); ++j) {
        if (quote) {
          if (text[j] == quote) quote = 0;
        } else if (text[j] == '"' || text[j] == '\'') {
          quote = text[j];
        } else if (text[j] == '>') {
          break;
        }
      }
      if (j >= text.size()) break;
      if (text[j - 1] != '/') open.emplace_back(n, i);
      i = j + 1;
    }
  }
  if (open.empty()) return false;
  *name = std::string(open.back().first);
  *open_at = open.back().second;
  closing->clear();
  return true;
}

// The second of two attributes with one name, or none. Elements have a handful of attributes:
// compared pairwise up to kFewAttributes, through a set beyond (an attack with thousands stays
// n log n).
constexpr int kFewAttributes = 8;

pugi::xml_attribute repeatedAttribute(const pugi::xml_node& n) {
  const pugi::xml_attribute first = n.first_attribute();
  if (!first || !first.next_attribute()) return {};  // most elements: one attribute or none
  int count = 0;
  for (pugi::xml_attribute a = n.first_attribute(); a && count <= kFewAttributes; a = a.next_attribute()) ++count;
  if (count <= kFewAttributes) {
    for (pugi::xml_attribute a = n.first_attribute(); a; a = a.next_attribute())
      for (pugi::xml_attribute b = n.first_attribute(); b != a; b = b.next_attribute())
        if (std::strcmp(a.name(), b.name()) == 0) return a;
    return {};
  }
  std::set<std::string_view> names;
  for (pugi::xml_attribute a = n.first_attribute(); a; a = a.next_attribute())
    if (!names.insert(a.name()).second) return a;
  return {};
}

}  // namespace

std::shared_ptr<XmlDoc> parseXml(std::string text, const Registry& reg, std::string* error, int* error_line,
                                 const std::function<std::string()>& reread) {
  auto d = std::make_shared<XmlDoc>();
  d->text = std::move(text);
  d->reg = &reg;
  const char* const begin = d->text.data();
  const char* const end = begin + d->text.size();
  for (const char* p = begin; (p = static_cast<const char*>(std::memchr(p, '\n', static_cast<size_t>(end - p)))); ++p)
    d->newlines.push_back(static_cast<size_t>(p - begin));
  pugi::xml_parse_result res =
      d->doc.load_buffer_inplace(d->text.data(), d->text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!res) {
    auto off = static_cast<size_t>(std::max<ptrdiff_t>(0, res.offset));
    *error_line =
        static_cast<int>(std::upper_bound(d->newlines.begin(), d->newlines.end(), off) - d->newlines.begin()) + 1;
    *error = std::string("malformed XML: ") + res.description();
    // pugixml says "Start-end tags mismatch" at the closing tag: name the element left open,
    // where it opens.
    std::string open, closing;
    size_t open_at = 0;
    // Parsing in place overwrote delimiters: the element a mismatched end tag leaves open is
    // found in the text as it was, asked for only now (a copy made for every scene cost a
    // second copy of its text while it was parsed). A text of another size is not the one parsed.
    std::string original;
    if (res.status == pugi::status_end_element_mismatch && reread) original = reread();
    if (original.size() == d->text.size() && !original.empty() &&
        unclosedElement(original, off, &open, &open_at, &closing)) {
      const int close_line = *error_line;
      *error_line =
          static_cast<int>(std::upper_bound(d->newlines.begin(), d->newlines.end(), open_at) - d->newlines.begin()) + 1;
      *error =
          "malformed XML: <" + quoteInput(open) + "> is not closed (" +
          (closing.empty() ? std::string("the file ends first")
                           : "</" + quoteInput(closing) + "> on line " + std::to_string(close_line) + " comes first") +
          ")";
    }
    return nullptr;
  }
  if (!d->doc.document_element()) {
    *error_line = 1;
    *error = "empty XML document";
    return nullptr;
  }
  // pugixml keeps the last of two equal attributes and accepts a second root element: both
  // would silently drop what the file says, so they are errors here.
  int roots = 0;
  for (pugi::xml_node n : d->doc.children()) {
    if (!isElement(n) || ++roots < 2) continue;
    *error_line = d->lineOf(n);
    *error = std::string("malformed XML: a second root element <") + n.name() + "> (a document has one)";
    return nullptr;
  }
  // pugixml walks the tree itself (in document order, so the first such element in the file is
  // named): a walk of our own cost several calls into the library for every element.
  struct RepeatedAttributes : pugi::xml_tree_walker {
    pugi::xml_node node;
    pugi::xml_attribute attribute;
    bool for_each(pugi::xml_node& n) override {
      if (!isElement(n)) return true;
      attribute = repeatedAttribute(n);
      if (!attribute) return true;
      node = n;
      return false;
    }
  } walk;
  d->doc.traverse(walk);  // every element below the document node: the root and all inside it
  if (walk.attribute) {
    *error_line = d->lineOf(walk.node);
    *error = std::string("malformed XML: attribute '") + walk.attribute.name() + "' given twice in <" +
             walk.node.name() + ">";
    return nullptr;
  }
  return d;
}

std::unique_ptr<Source> xmlRoot(const std::shared_ptr<XmlDoc>& doc, std::string* root_name) {
  pugi::xml_node root = doc->doc.document_element();
  *root_name = root.name();
  return std::make_unique<XmlSource>(doc, root);
}

std::unique_ptr<Source> xmlDocument(const std::shared_ptr<XmlDoc>& doc) {
  return std::make_unique<XmlSource>(doc, doc->doc);
}

}  // namespace simbob
