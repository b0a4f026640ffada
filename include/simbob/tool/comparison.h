// Golden trajectory comparison: the library part of
// `simbob compare ACTUAL GOLDEN [--tol-pos M] [--tol-rot RAD]`.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "simbob/trajectory.h"

namespace simbob {

/// Tolerances of a comparison. An error equal to the tolerance passes; a larger one (or NaN)
/// exceeds it. Defaults: tol_pos = 1e-6 m, tol_rot = 1e-6 rad; sample times match when they
/// differ by at most time_eps = 1e-9 s.
struct CompareOptions {
  double tol_pos = 1e-6;   ///< max position error, m (Euclidean distance)
  double tol_rot = 1e-6;   ///< max rotation error, rad (angle of the relative rotation)
  double time_eps = 1e-9;  ///< sample times closer than this are the same sample, s
};

/// Results for one body present in both trajectories. Times are the golden file's.
struct BodyDiff {
  std::string body;
  size_t compared = 0;                       ///< shared samples where both have a row
  double max_pos_err = 0;                    ///< m
  double max_pos_time = 0;                   ///< time of the first occurrence of max_pos_err (if compared > 0)
  double max_rot_err = 0;                    ///< rad
  double max_rot_time = 0;                   ///< time of the first occurrence of max_rot_err (if compared > 0)
  std::optional<double> first_exceed_time;   ///< earliest time a tolerance was exceeded
  double first_exceed_pos_err = 0;           ///< position error at first_exceed_time
  double first_exceed_rot_err = 0;           ///< rotation error at first_exceed_time
  size_t missing_in_actual = 0;              ///< shared times where only golden has a row for this body
  size_t missing_in_golden = 0;              ///< shared times where only actual has a row for this body
  std::optional<double> first_missing_time;  ///< earliest such time

  bool exceeded() const { return first_exceed_time.has_value(); }
  bool missingRows() const { return missing_in_actual + missing_in_golden > 0; }
  bool pass() const { return !exceeded() && !missingRows(); }
};

/// Sample times present in only one of the trajectories.
struct TimeMismatch {
  size_t count = 0;
  std::optional<double> first_time;  ///< earliest such time
};

/// The earliest point where any body exceeded a tolerance.
struct Divergence {
  double time = 0;
  std::string body;
  double pos_err = 0;  ///< m
  double rot_err = 0;  ///< rad
  bool pos_exceeded = false;
  bool rot_exceeded = false;
};

/// Outcome of compareTrajectories().
struct CompareResult {
  bool pass = false;  ///< no structural mismatch and every body within both tolerances
  CompareOptions options;
  size_t actual_samples = 0;
  size_t golden_samples = 0;
  size_t shared_samples = 0;
  std::vector<BodyDiff> bodies;          ///< bodies in both, in golden order
  std::vector<std::string> only_actual;  ///< bodies only in actual, in actual order
  std::vector<std::string> only_golden;  ///< bodies only in golden, in golden order
  TimeMismatch times_only_actual;
  TimeMismatch times_only_golden;
  std::optional<Divergence> first_divergence;

  /// True when the trajectories differ in bodies, sample times or rows.
  bool structuralMismatch() const;

  /// Human-readable report: a table (body, max pos err, max rot err, first exceed time,
  /// status) followed by summary lines and a final "result: PASS|FAIL" line.
  std::string text() const;

  /// Machine-readable report with the same content. Absent times are null.
  nlohmann::json json() const;
};

/// Euclidean distance between the positions p1[0..2] and p2[0..2].
double positionError(const double* p1, const double* p2);

/// Angle (rad, in [0, pi]) of the rotation between quaternions q1 and q2 (w x y z), invariant
/// to sign (q and -q are the same rotation) and to scale. Computed as
/// 2*atan2(|vec(conj(q1)*q2)|, |scalar(conj(q1)*q2)|), accurate for tiny angles.
double rotationError(const double* q1, const double* q2);

/// Compares actual against golden: bodies matched by key, samples by time (within time_eps).
CompareResult compareTrajectories(const Trajectory& actual, const Trajectory& golden,
                                  const CompareOptions& options = {});

}  // namespace simbob
