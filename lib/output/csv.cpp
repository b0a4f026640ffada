// See simbob/tool/csv.h.
#include "simbob/tool/csv.h"

#include <cstring>

namespace simbob {

std::string csvField(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';  // a quote is escaped by doubling it
    out += c;
  }
  out += '"';
  return out;
}

CsvReader::CsvReader(std::string_view text, const std::string& path)
    : path_(path), p_(text.data()), end_(text.data() + text.size()) {
  if (end_ - p_ >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) p_ += 3;
}

bool CsvReader::fail(Error* err, const std::string& message) {
  if (err) *err = {ErrorKind::InvalidInput, {path_, record_line_}, message};
  p_ = end_;
  return false;
}

bool CsvReader::next(Error* err) {
  // Blank lines (e.g. a trailing one added by an editor) carry no record.
  while (p_ < end_ && (*p_ == '\n' || (*p_ == '\r' && p_ + 1 < end_ && p_[1] == '\n'))) {
    p_ += (*p_ == '\n') ? 1 : 2;
    ++line_;
  }
  if (p_ >= end_) return false;
  record_line_ = line_;
  const char* nl = static_cast<const char*>(std::memchr(p_, '\n', static_cast<size_t>(end_ - p_)));
  raw_ = std::string_view(p_, static_cast<size_t>((nl ? nl : end_) - p_));
  if (!raw_.empty() && raw_.back() == '\r') raw_.remove_suffix(1);
  fields_.clear();
  size_t quoted = 0;
  for (;;) {
    std::string_view f;
    if (p_ < end_ && *p_ == '"') {
      ++p_;
      if (unquoted_.size() <= quoted) unquoted_.emplace_back();
      std::string& s = unquoted_[quoted++];
      s.clear();
      for (;;) {
        if (p_ == end_) return fail(err, "unterminated quoted field");
        const char c = *p_++;
        if (c == '"') {
          if (p_ < end_ && *p_ == '"') {
            s += '"';
            ++p_;
            continue;
          }
          break;
        }
        if (c == '\n') ++line_;
        s += c;
      }
      if (p_ < end_ && *p_ == '\r' && (p_ + 1 == end_ || p_[1] == '\n')) ++p_;
      if (p_ < end_ && *p_ != ',' && *p_ != '\n') return fail(err, "unexpected character after closing quote");
      f = s;
    } else {
      const char* b = p_;
      while (p_ < end_ && *p_ != ',' && *p_ != '\n') {
        if (*p_ == '"') return fail(err, "unexpected '\"' in unquoted field");
        ++p_;
      }
      f = std::string_view(b, static_cast<size_t>(p_ - b));
      if (!f.empty() && f.back() == '\r' && (p_ == end_ || *p_ == '\n')) f.remove_suffix(1);
    }
    fields_.push_back(f);
    if (p_ == end_) return true;
    if (*p_ == ',') {
      ++p_;
      continue;
    }
    ++p_;  // '\n'
    ++line_;
    return true;
  }
}

}  // namespace simbob
