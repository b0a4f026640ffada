// The reference of load_bench.py's parse comparison (issue 32, point 2): read a scene file and
// parse it with pugixml as lib/scene/xml_source.cpp does (the whole file in memory, parsed in
// place with parse_default), and nothing else. Prints the element count so the parse is not
// optimised away.
//
// Usage: bare_parse FILE.xml
#include <cstdio>
#include <fstream>
#include <iterator>
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
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "bare_parse: cannot read %s\n", argv[1]);
    return 66;
  }
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  pugi::xml_document doc;
  const pugi::xml_parse_result r = doc.load_buffer_inplace(text.data(), text.size(), pugi::parse_default,
                                                           pugi::encoding_utf8);
  if (!r) {
    std::fprintf(stderr, "bare_parse: %s: %s\n", argv[1], r.description());
    return 65;
  }
  std::printf("%zu elements\n", countElements(doc));
  return 0;
}
