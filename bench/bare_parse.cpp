// The reference of load_bench.py's parse comparison (issue 32, point 2): read a scene file and
// parse it with pugixml as lib/scene/xml_source.cpp does (the whole file in memory, parsed in
// place with parse_default), and nothing else. Prints the element count so the parse is not
// optimised away.
//
// Usage: bare_parse FILE.xml
#include <cstdio>
#include <pugixml.hpp>
#include <string>

namespace {

size_t countElements(const pugi::xml_node& n) {
  size_t k = n.type() == pugi::node_element ? 1 : 0;
  for (pugi::xml_node c : n.children()) k += countElements(c);
  return k;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bare_parse FILE.xml\n");
    return 64;
  }
  // Read in one piece, as lib/scene's readFile does (an istreambuf_iterator copy costs more
  // instructions than the parse itself and would flatter every ratio against it).
  std::FILE* f = std::fopen(argv[1], "rb");
  std::string text;
  bool read = f != nullptr && std::fseek(f, 0, SEEK_END) == 0;
  const long size = read ? std::ftell(f) : -1;
  read = read && size >= 0 && std::fseek(f, 0, SEEK_SET) == 0;
  if (read) {
    text.resize(static_cast<size_t>(size));
    read = std::fread(text.data(), 1, text.size(), f) == text.size();
  }
  if (f) std::fclose(f);
  if (!read) {
    std::fprintf(stderr, "bare_parse: cannot read %s\n", argv[1]);
    return 66;
  }
  pugi::xml_document doc;
  const pugi::xml_parse_result r =
      doc.load_buffer_inplace(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!r) {
    std::fprintf(stderr, "bare_parse: %s: %s\n", argv[1], r.description());
    return 65;
  }
  std::printf("%zu elements\n", countElements(doc));
  return 0;
}
