// CSV (include/simbob/tool/csv.h): what csvField writes, CsvReader reads back unchanged; malformed
// records are named by the line they start on.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "simbob/tool/csv.h"

using namespace simbob;

TEST_CASE("csvField quotes only what needs it, and CsvReader reads every field back", "[csv]") {
  const std::vector<std::string> fields = {"plain", "a,b", "say \"hi\"", "two\nlines", "cr\r", "Châssis", "", "x"};
  CHECK(csvField("plain") == "plain");
  CHECK(csvField("a,b") == "\"a,b\"");
  CHECK(csvField("say \"hi\"") == "\"say \"\"hi\"\"\"");
  std::string text;
  for (int row = 0; row < 3; ++row) {
    for (size_t i = 0; i < fields.size(); ++i) text += (i ? "," : "") + csvField(fields[i]);
    text += row == 1 ? "\r\n" : "\n";
  }
  const std::string path = "t.csv";
  CsvReader csv(text, path);
  Error err;
  int records = 0;
  while (csv.next(&err)) {
    // Eight fields, four of them quoted: their storage must hold while the record is read.
    REQUIRE(csv.fields().size() == fields.size());
    for (size_t i = 0; i < fields.size(); ++i) CHECK(std::string(csv.fields()[i]) == fields[i]);
    ++records;
  }
  CHECK(err.message.empty());
  CHECK(records == 3);
}

TEST_CASE("CsvReader skips a byte order mark and blank lines, and names the line of a bad record", "[csv]") {
  const std::string path = "t.csv";
  {
    CsvReader csv("\xEF\xBB\xBFh1,h2\n\n1,2\n", path);
    Error err;
    REQUIRE(csv.next(&err));
    CHECK(csv.fields()[0] == "h1");
    REQUIRE(csv.next(&err));
    CHECK(csv.line() == 3);
    CHECK_FALSE(csv.next(&err));
    CHECK(err.message.empty());
  }
  struct Bad {
    const char* text;
    const char* message;
    int line;
  };
  for (const Bad& b : {Bad{"a,b\n\"open,\n", "unterminated quoted field", 2},
                       Bad{"a,b\n1,\"q\"x\n", "unexpected character after closing quote", 2},
                       Bad{"a\n\"multi\nline\",ok\n1,x\"y\n", "unexpected '\"' in unquoted field", 4}}) {
    CsvReader csv(b.text, path);
    Error err;
    while (csv.next(&err)) {
    }
    CHECK(err.message == b.message);
    CHECK(err.loc.line == b.line);
    CHECK(err.str() == "t.csv:" + std::to_string(b.line) + ": " + b.message);
  }
}
