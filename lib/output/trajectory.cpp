#include "simbob/tool/csv.h"
#include "simbob/trajectory.h"

#include "simbob/tool/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "simbob/values.h"

namespace simbob {

namespace {

/// Buffered bytes that trigger a write; large enough to amortise syscalls.
constexpr size_t kFlushBytes = size_t{1} << 20;

constexpr size_t kFieldCount = 9;
constexpr size_t kVelocityFieldCount = kFieldCount + kVelocitySize;

/// Trajectories are stored densely (every body at every sample time), so a sparse file (each
/// row a new body at a new time) needs memory quadratic in its size. Bound the dense storage
/// to this many cells per row, beyond a fixed allowance of kSparseAllowance cells.
constexpr size_t kMaxCellsPerRow = 16;
constexpr size_t kSparseAllowance = size_t{1} << 20;
constexpr const char* kColumnNames[kVelocityFieldCount] = {"time", "body", "x",  "y",  "z",  "qw", "qx", "qy",
                                                           "qz",   "vx",   "vy", "vz", "wx", "wy", "wz"};

Error makeError(ErrorKind kind, const std::string& file, int line, std::string message) {
  Error e;
  e.kind = kind;
  e.loc.file = file;
  e.loc.line = line;
  e.message = std::move(message);
  return e;
}

void setError(Error* err, Error e) {
  if (err) *err = std::move(e);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// TrajectoryWriter

std::unique_ptr<TrajectoryWriter> TrajectoryWriter::open(const std::string& final_path,
                                                         std::vector<std::string> body_keys, Error* err,
                                                         bool velocity) {
  std::unordered_set<std::string> seen;
  for (const std::string& key : body_keys) {
    if (key.empty()) {
      setError(err, makeError(ErrorKind::Internal, final_path, 0, "empty body key"));
      return nullptr;
    }
    if (!seen.insert(key).second) {
      setError(err, makeError(ErrorKind::Internal, final_path, 0, "duplicate body key '" + key + "'"));
      return nullptr;
    }
  }

  std::unique_ptr<TrajectoryWriter> w(new TrajectoryWriter());
  w->final_path_ = final_path;
  w->out_ = OutputFile::open(final_path, err);
  if (!w->out_) {
    w->done_ = true;  // nothing to clean up
    return nullptr;
  }
  w->keys_ = std::move(body_keys);
  w->encoded_keys_.reserve(w->keys_.size());
  for (const std::string& key : w->keys_) w->encoded_keys_.push_back(csvField(key));
  w->buf_.reserve(kFlushBytes + 4096);
  w->velocity_ = velocity;
  w->buf_ += velocity ? kTrajectoryVelocityHeader : kTrajectoryHeader;
  w->buf_ += '\n';
  return w;
}

TrajectoryWriter::~TrajectoryWriter() { abandon(); }

bool TrajectoryWriter::isStream() const { return out_ && out_->isStream(); }

const std::string& TrajectoryWriter::tempPath() const {
  static const std::string none;
  return out_ ? out_->tempPath() : none;
}

bool TrajectoryWriter::addSample(double time, const double* poses, const double* velocities) {
  std::lock_guard<std::timed_mutex> lock(mu_);
  if (done_ || failed_) return false;
  // The time text is the same for every body of the sample: format it once.
  time_text_.clear();
  appendNumber(time_text_, time);
  const size_t n = encoded_keys_.size();
  for (size_t b = 0; b < n; ++b) {
    buf_ += time_text_;
    buf_ += ',';
    buf_ += encoded_keys_[b];
    const double* p = poses + b * kPoseSize;
    for (size_t k = 0; k < kPoseSize; ++k) {
      buf_ += ',';
      appendNumber(buf_, p[k]);
    }
    if (velocity_) {
      const double* v = velocities + b * kVelocitySize;
      for (size_t k = 0; k < kVelocitySize; ++k) {
        buf_ += ',';
        appendNumber(buf_, v[k]);
      }
    }
    buf_ += '\n';
  }
  if (buf_.size() >= kFlushBytes) return flush();
  return true;
}

bool TrajectoryWriter::flush() {
  if (failed_) return false;
  if (buf_.empty()) return true;
  if (!out_->write(buf_)) {
    failed_ = true;
    return false;
  }
  flushed_ += buf_.size();
  buf_.clear();
  return true;
}

bool TrajectoryWriter::finish(const std::string& target, Error* err, const std::vector<OutputFile*>& also) {
  if (done_) {
    setError(err, makeError(ErrorKind::Internal, final_path_, 0, "trajectory writer already closed"));
    return false;
  }
  flush();
  std::vector<OutputFile*> all = {out_.get()};
  all.insert(all.end(), also.begin(), also.end());
  bool ok;
  if (target.empty()) {
    ok = commitOutputs(all, err);
  } else {
    ok = out_->close(err) && out_->rename(target, err);
  }
  if (!ok) failed_ = true;
  buf_.clear();
  done_ = true;
  return ok;
}

bool TrajectoryWriter::commit(Error* err, const std::vector<OutputFile*>& also) { return finish("", err, also); }

bool TrajectoryWriter::keepPartial(const std::string& partial_path, Error* err) {
  if (out_ && out_->isStream()) return finish("", err, {});
  return finish(partial_path, err, {});
}

bool TrajectoryWriter::keepPartialFromOtherThread(const std::string& partial_path, Error* err) {
  // Never unlocked: the other thread must not add anything after this. A write that blocks
  // (a FIFO nobody reads) must not hold the caller forever.
  if (!mu_.try_lock_for(std::chrono::milliseconds(500))) {
    setError(err, makeError(ErrorKind::IoError, final_path_, 0, "a write in progress did not finish; nothing kept"));
    return false;
  }
  return keepPartial(partial_path, err);
}

void TrajectoryWriter::abandon() {
  if (done_) return;
  if (out_) out_->abandon();
  buf_.clear();
  done_ = true;
}

// ---------------------------------------------------------------------------------------------
// Trajectory

size_t Trajectory::addBody(std::string key) {
  bodies.push_back(std::move(key));
  poses.emplace_back();
  present.emplace_back();
  return bodies.size() - 1;
}

void Trajectory::setPose(size_t s, size_t b, const double* pose7) {
  std::vector<double>& column = poses[b];
  std::vector<uint8_t>& flags = present[b];
  if (flags.size() <= s) {
    // Grows to times.size() rather than s+1 so appending samples stays amortised O(1).
    size_t n = times.size() > s ? times.size() : s + 1;
    flags.resize(n, 0);
    column.resize(n * kPoseSize, 0.0);
  }
  std::copy(pose7, pose7 + kPoseSize, column.begin() + static_cast<std::ptrdiff_t>(s * kPoseSize));
  flags[s] = 1;
}

void Trajectory::setVelocity(size_t s, size_t b, const double* velocity6) {
  if (velocities.size() < bodies.size()) velocities.resize(bodies.size());
  std::vector<double>& column = velocities[b];
  if (column.size() < (s + 1) * kVelocitySize) column.resize((times.size() > s ? times.size() : s + 1) * kVelocitySize);
  std::copy(velocity6, velocity6 + kVelocitySize, column.begin() + static_cast<std::ptrdiff_t>(s * kVelocitySize));
}

void Trajectory::finalize() {
  if (has_velocity) velocities.resize(bodies.size());
  for (size_t b = 0; b < bodies.size(); ++b) {
    present[b].resize(times.size(), 0);
    poses[b].resize(times.size() * kPoseSize, 0.0);
    if (has_velocity) velocities[b].resize(times.size() * kVelocitySize, 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// readTrajectory

namespace {

bool looksLikeNan(std::string_view f) {
  if (!f.empty() && (f[0] == '-' || f[0] == '+')) f.remove_prefix(1);
  return f.size() == 3 && (f[0] == 'n' || f[0] == 'N') && (f[1] == 'a' || f[1] == 'A') && (f[2] == 'n' || f[2] == 'N');
}

/// Whether s is well-formed UTF-8 (no overlong forms, surrogates or code points > U+10FFFF).
/// Body keys end up in JSON reports, which must be valid UTF-8.
bool isValidUtf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (c < 0x80)
      n = 0;
    else if (c >= 0xC2 && c <= 0xDF)
      n = 1;
    else if (c == 0xE0)
      n = 2, lo = 0xA0;
    else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF)
      n = 2;
    else if (c == 0xED)
      n = 2, hi = 0x9F;
    else if (c == 0xF0)
      n = 3, lo = 0x90;
    else if (c >= 0xF1 && c <= 0xF3)
      n = 3;
    else if (c == 0xF4)
      n = 3, hi = 0x8F;
    else
      return false;
    if (s.size() - i <= n) return false;  // truncated sequence
    for (size_t k = 1; k <= n; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return false;
    }
    i += n + 1;
  }
  return true;
}

/// Field text for messages: bounded, so a garbage line does not flood the terminal.
std::string quoteForMessage(std::string_view f) {
  constexpr size_t kMax = 60;
  std::string out = "'";
  if (f.size() > kMax) {
    out.append(f.substr(0, kMax));
    out += "...";
  } else {
    out.append(f);
  }
  out += "'";
  return out;
}

// Reads a trajectory CSV's records (CsvReader) into a Trajectory, checking every row.
class TrajectoryParser {
 public:
  TrajectoryParser(const std::string& path, std::string_view text) : path_(path), csv_(text, path) {}

  bool run(Trajectory* out, Error* err);

 private:
  bool fail(Error* err, int line, std::string message) {
    setError(err, makeError(ErrorKind::InvalidInput, path_, line, std::move(message)));
    return false;
  }

  const std::string& path_;
  CsvReader csv_;
};

bool TrajectoryParser::run(Trajectory* out, Error* err) {
  // Header: the whole first line, compared verbatim.
  Error header_err;
  const bool have_header = csv_.next(&header_err);
  if (!have_header && header_err.message.empty())
    return fail(err, 0, std::string("empty file, expected header ") + kTrajectoryHeader);
  const std::string_view header = csv_.rawLine();
  const bool velocity = header == kTrajectoryVelocityHeader;
  if (!have_header || (header != kTrajectoryHeader && !velocity))
    return fail(err, 1,
                std::string("expected header '") + kTrajectoryHeader + "' (or with ',vx,vy,vz,wx,wy,wz'), found " +
                    quoteForMessage(header));
  const size_t fields = velocity ? kVelocityFieldCount : kFieldCount;

  Trajectory& t = *out;
  t = Trajectory();
  t.has_velocity = velocity;
  std::unordered_map<std::string, size_t> index;
  std::string key;
  size_t last_body = 0;
  size_t rows = 0;
  double pose[kPoseSize];

  Error record_err;
  while (csv_.next(&record_err)) {
    const std::vector<std::string_view>& fields_ = csv_.fields();
    const int line = csv_.line();
    if (fields_.size() != fields)
      return fail(err, line, "expected " + std::to_string(fields) + " fields, found " + std::to_string(fields_.size()));

    double values[kVelocityFieldCount] = {};
    for (size_t i = 0; i < fields; ++i) {
      if (i == 1) continue;
      std::string_view f = fields_[i];
      if (looksLikeNan(f)) return fail(err, line, std::string("NaN in column ") + kColumnNames[i]);
      std::optional<double> v = parseNumber(f);
      if (!v) return fail(err, line, "bad number " + quoteForMessage(f) + " in column " + kColumnNames[i]);
      values[i] = *v;
    }
    for (size_t k = 0; k < kPoseSize; ++k) pose[k] = values[2 + k];
    const double time = values[0];
    std::string_view body = fields_[1];
    if (body.empty()) return fail(err, line, "empty body key");
    if (!isValidUtf8(body)) return fail(err, line, "body key is not valid UTF-8");
    // A NUL would cut the key wherever it is used as a C string (plots, messages).
    if (body.find('\0') != std::string_view::npos) return fail(err, line, "body key contains a NUL byte");
    // Rotation errors are angles between quaternions (scaled to unit length): a zero one is no
    // rotation, and comparing with it gave "nan".
    if (pose[3] == 0 && pose[4] == 0 && pose[5] == 0 && pose[6] == 0)
      return fail(err, line, "quaternion qw qx qy qz is zero: not a rotation");

    if (t.times.empty() || time != t.times.back()) {
      if (!t.times.empty() && time < t.times.back()) {
        std::string msg = "time ";
        appendNumber(msg, time);
        msg += " is before the previous time ";
        appendNumber(msg, t.times.back());
        return fail(err, line, std::move(msg));
      }
      t.times.push_back(time);
    }
    const size_t s = t.times.size() - 1;

    // Rows usually cycle through the bodies in the same order: try the next one first.
    size_t b = t.bodies.size();
    const size_t guess = last_body + 1 < t.bodies.size() ? last_body + 1 : 0;
    if (guess < t.bodies.size() && t.bodies[guess] == body) {
      b = guess;
    } else {
      key.assign(body.data(), body.size());
      auto it = index.find(key);
      if (it != index.end()) {
        b = it->second;
      } else {
        b = t.addBody(key);
        index.emplace(key, b);
      }
    }
    last_body = b;

    if (t.pose(s, b) != nullptr) {
      std::string msg = "duplicate row for body " + quoteForMessage(body) + " at time ";
      appendNumber(msg, time);
      return fail(err, line, std::move(msg));
    }
    ++rows;
    const size_t cells = t.bodies.size() * t.times.size();
    if (cells > kSparseAllowance && cells / kMaxCellsPerRow > rows)
      return fail(err, line,
                  "too sparse to hold: " + std::to_string(t.bodies.size()) + " bodies at " +
                      std::to_string(t.times.size()) + " sample times but only " + std::to_string(rows) +
                      " rows (every body needs a row at most sample times)");
    t.setPose(s, b, pose);
    if (velocity) t.setVelocity(s, b, values + kFieldCount);
  }
  if (!record_err.message.empty()) {
    setError(err, record_err);
    return false;
  }
  t.finalize();
  return true;
}

}  // namespace

bool readTrajectory(const std::string& path, Trajectory* out, Error* err) {
  std::string text, reason;
  bool too_large = false;
  if (!readFile(path, kMaxTrajectoryFileBytes, &text, &reason, false, &too_large)) {
    // Too large is what the file holds (65, README's limits), not a file that is missing (66).
    setError(err, makeError(too_large ? ErrorKind::InvalidInput : ErrorKind::MissingInput, path, 0,
                            "cannot read: " + reason));
    return false;
  }
  Trajectory t;
  TrajectoryParser parser(path, text);
  if (!parser.run(&t, err)) return false;
  *out = std::move(t);
  return true;
}

}  // namespace simbob
