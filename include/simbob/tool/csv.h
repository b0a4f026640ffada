// CSV as simbob writes and reads it (RFC 4180): the trajectory, the run log, sweep tables. One
// writer of fields and one reader of records, so every file quotes and parses alike.
#pragma once

#include <deque>
#include <string>
#include <string_view>
#include <vector>

#include "simbob/error.h"

namespace simbob {

/// A field as written: as it is, or -- when it holds a comma, a double quote, CR or LF -- in
/// double quotes with its quotes doubled.
std::string csvField(std::string_view text);

/// Reads records one at a time. A quoted field may hold commas, doubled quotes and line breaks;
/// a CR before a line end is not part of the record. Fields are views into the text, or into the
/// reader's own storage for quoted fields: valid until the next call of next().
class CsvReader {
 public:
  /// `path` names the text in errors. A UTF-8 byte order mark at the start is skipped.
  CsvReader(std::string_view text, const std::string& path);
  /// The next record into fields(); blank lines are skipped. False at the end of the text (err
  /// untouched), or for a malformed record: *err (ErrorKind::InvalidInput, the line where the
  /// record starts) says what is wrong.
  bool next(Error* err);
  const std::vector<std::string_view>& fields() const { return fields_; }
  /// The line where the last record read starts (1-based).
  int line() const { return record_line_; }
  /// The raw text of the record's first line, without its line end (for messages).
  std::string_view rawLine() const { return raw_; }

 private:
  bool fail(Error* err, const std::string& message);
  const std::string& path_;
  const char* p_;
  const char* end_;
  int line_ = 1;
  int record_line_ = 0;
  std::string_view raw_;
  std::vector<std::string_view> fields_;
  std::deque<std::string> unquoted_;  ///< storage of the quoted fields (stable as it grows)
};

}  // namespace simbob
