// Trajectory CSV files (user contract): a header line `time,body,x,y,z,qw,qx,qy,qz`, then one
// row per body per sample ("long format"), numbers in shortest round-trip form, '\n' line ends.
// Body keys containing ',', '"', CR or LF are quoted CSV-style ("..." with "" doubling).
// Optionally (`run --columns pose,velocity`) a velocity block follows the pose on every row:
// `vx,vy,vz` (m/s) and `wx,wy,wz` (rad/s), world frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "simbob/error.h"

namespace simbob {

/// The exact header line of a trajectory CSV (without the line end).
inline constexpr const char* kTrajectoryHeader = "time,body,x,y,z,qw,qx,qy,qz";

/// The header line of a trajectory CSV with the velocity block.
inline constexpr const char* kTrajectoryVelocityHeader = "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";

/// Doubles per body per sample: x y z qw qx qy qz.
inline constexpr size_t kPoseSize = 7;

/// Doubles of the velocity block per body per sample: vx vy vz (m/s) wx wy wz (rad/s).
inline constexpr size_t kVelocitySize = 6;

class OutputFile;  // simbob/tool/files.h

/// Streams a trajectory CSV to an OutputFile (simbob/tool/files.h): a temporary file next to the
/// final path, moved into place only on commit(), so a failed or interrupted run never leaves a
/// truncated file under the final name; a device or FIFO is written through instead. Output is
/// buffered (flushed in ~1 MiB blocks) and formatted with std::to_chars.
class TrajectoryWriter {
 public:
  /// Opens the output (see OutputFile::open) and writes the header into the buffer. Nothing is
  /// created under final_path until commit(). body_keys are fully qualified keys in output
  /// order; they must be non-empty and distinct (ErrorKind::Internal otherwise). Returns
  /// nullptr and sets *err on failure (ErrorKind::CannotCreate when the output cannot be made).
  /// With `velocity`, every row also holds the velocity block (kTrajectoryVelocityHeader).
  static std::unique_ptr<TrajectoryWriter> open(const std::string& final_path, std::vector<std::string> body_keys,
                                                Error* err, bool velocity = false);

  /// Abandons the output (removes the temporary file) unless commit() or keepPartial() was called.
  ~TrajectoryWriter();

  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

  /// Appends one row per body. `poses` holds kPoseSize doubles per body, in body order
  /// (x y z qw qx qy qz). Returns false once a write has failed (the error is reported by
  /// commit()/keepPartial()) or after the writer was closed; the sample is then dropped.
  /// `velocities` (kVelocitySize doubles per body, in body order) is read only by a writer
  /// opened with velocity, which needs it.
  bool addSample(double time, const double* poses, const double* velocities = nullptr);

  /// Whether rows carry the velocity block.
  bool withVelocity() const { return velocity_; }

  /// Flushes, closes and renames the temporary file to final_path (atomically replacing an
  /// existing file), together with `also` (the run's other outputs): all are replaced, or none
  /// (see commitOutputs). On failure the temporary files are removed, *err is set
  /// (ErrorKind::IoError for a failed write, ErrorKind::CannotCreate for a failed rename)
  /// and false is returned.
  bool commit(Error* err, const std::vector<OutputFile*>& also = {});

  /// Like commit() but renames to partial_path: keeps what was recorded by a failed or
  /// interrupted run without touching final_path. If a write had failed, nothing is kept.
  /// A stream output has nothing to rename: what was recorded has gone through.
  bool keepPartial(const std::string& partial_path, Error* err);

  /// keepPartial() from another thread while the thread that adds samples may be stopped in
  /// the middle of anything (an interrupted run whose step does not end): keeps the samples
  /// added completely so far. The writer is closed for good afterwards (addSample blocks), so
  /// call it only right before ending the process.
  bool keepPartialFromOtherThread(const std::string& partial_path, Error* err);

  /// Closes and removes the temporary file; no-op after commit()/keepPartial().
  void abandon();

  /// Bytes produced so far, header included (written plus still buffered): the size the file
  /// will have once committed.
  uint64_t bytesWritten() const { return flushed_ + buf_.size(); }

  /// False once a write has failed.
  bool ok() const { return !failed_; }

  /// Whether the output is written through (a device, FIFO or stdout) rather than renamed.
  bool isStream() const;

  const std::string& finalPath() const { return final_path_; }
  const std::string& tempPath() const;

 private:
  TrajectoryWriter() = default;
  bool flush();
  bool finish(const std::string& target, Error* err, const std::vector<OutputFile*>& also);

  std::string final_path_;
  std::unique_ptr<OutputFile> out_;
  std::vector<std::string> keys_;
  std::vector<std::string> encoded_keys_;  ///< keys as written (quoted when needed)
  std::string buf_;
  std::string time_text_;
  uint64_t flushed_ = 0;
  bool failed_ = false;
  bool velocity_ = false;
  bool done_ = false;    ///< committed, kept or abandoned
  std::timed_mutex mu_;  ///< held while a sample is added: keepPartialFromOtherThread sees whole samples
};

/// A trajectory in memory. Storage is per body: poses[b] holds kPoseSize doubles per sample and
/// present[b][s] says whether a row existed for body b at sample s.
struct Trajectory {
  std::vector<std::string> bodies;              ///< in order of first appearance
  std::vector<double> times;                    ///< distinct sample times, increasing
  std::vector<std::vector<double>> poses;       ///< [body] -> kPoseSize * times.size()
  std::vector<std::vector<uint8_t>> present;    ///< [body] -> times.size() flags
  bool has_velocity = false;                    ///< the file had the velocity block
  std::vector<std::vector<double>> velocities;  ///< [body] -> kVelocitySize * times.size() (has_velocity)

  /// The kVelocitySize doubles of body b at sample s, or nullptr when the row is missing or the
  /// file had no velocity block.
  const double* velocity(size_t s, size_t b) const {
    if (!has_velocity || !pose(s, b)) return nullptr;
    return velocities[b].data() + s * kVelocitySize;
  }

  size_t sampleCount() const { return times.size(); }
  size_t bodyCount() const { return bodies.size(); }

  /// The kPoseSize doubles of body b at sample s, or nullptr when that row is missing.
  const double* pose(size_t s, size_t b) const {
    if (b >= present.size() || s >= present[b].size() || !present[b][s]) return nullptr;
    return poses[b].data() + s * kPoseSize;
  }

  /// Adds a body (no duplicate check) and returns its index.
  size_t addBody(std::string key);

  /// Stores the pose of body b at sample s and marks the row present. Requires
  /// b < bodies.size() and s < times.size(); storage grows as needed.
  void setPose(size_t s, size_t b, const double* pose7);
  /// Stores the velocity block of body b at sample s (call after setPose for that row).
  void setVelocity(size_t s, size_t b, const double* velocity6);

  /// Sizes every per-body column to times.size() (missing rows stay absent).
  void finalize();
};

/// Reads a trajectory CSV (whole file in memory, linear time). Rows for one time must be
/// contiguous; times must not decrease. Errors name the file and line: ErrorKind::MissingInput
/// when the file cannot be read, ErrorKind::InvalidInput for a wrong header, wrong field count,
/// bad number, NaN, time going backwards or a duplicate (time, body) row.
bool readTrajectory(const std::string& path, Trajectory* out, Error* err);

}  // namespace simbob
