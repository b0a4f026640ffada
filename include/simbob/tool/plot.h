// Trajectory plots: the library part of `simbob plot`. Three stacked panels x(t), y(t), z(t)
// with one coloured line per body and, optionally, the golden trajectory dashed in the same
// colour. Rendered with cairo to PNG or SVG; the format follows the output file's extension.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/trajectory.h"

namespace simbob {

/// At most this many bodies share one plot (the palette has this many colours).
inline constexpr size_t kMaxPlotBodies = 8;

/// What to plot and how big.
struct PlotOptions {
  /// Body keys to plot, in legend order. Empty = every body of the actual trajectory, capped at
  /// kMaxPlotBodies (the title then says "first 8 of N bodies"). Naming more than
  /// kMaxPlotBodies bodies is an error; duplicates are ignored.
  std::vector<std::string> bodies;
  /// Headline of the image; empty = "trajectory".
  std::string title;
  /// Image width in pixels (SVG: CSS px), 200..10000.
  int width = 1200;
  /// Image height in pixels; 0 = 300 px per panel (900). Otherwise 300..10000.
  int height = 0;
  /// Panels drawn, 1..3: the first `panels` of x, y, z (a sweep table's metric is one panel).
  int panels = 3;
  /// Titles of the panels instead of "x [m]", "y [m]", "z [m]" (empty = those).
  std::vector<std::string> panel_titles;
  /// Adds a panel after the position panels: each body's rotation from its first orientation
  /// (rad, the angle of q_first^-1 q), so that a change that is a rotation (a pendulum off by
  /// 0.08 rad) shows as one, and not only as the small motion of a frame near its hinge.
  bool rotation = false;
  /// Label of the horizontal axis instead of "time [s]" (empty = that).
  std::string time_label;
};

/// An 8-bit sRGB colour.
struct PlotColor {
  uint8_t r = 0;
  uint8_t g = 0;
  uint8_t b = 0;
};

/// The line colour of the i-th plotted body (fixed palette, cycles after kMaxPlotBodies).
inline PlotColor plotColor(size_t i) {
  // Tableau-like palette: distinct hues that stay readable on white and print in grey.
  constexpr PlotColor kPalette[kMaxPlotBodies] = {
      {31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
      {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {23, 190, 207},
  };
  return kPalette[i % kMaxPlotBodies];
}

/// Plots `actual` (solid lines) and, when `golden` is not null and has samples, the golden
/// trajectory (dashed, same colour per body) into out_path. The format comes from the
/// extension, case-insensitive: ".png" or ".svg". The time axis spans both trajectories; long
/// trajectories are decimated to a few points per pixel column, so plotting is linear in the
/// sample count. Same input -> same PNG or SVG bytes. The file is written to
/// "<out_path>.tmp.<pid>" and renamed into place. Errors (*err set if not null, false returned):
/// ErrorKind::InvalidInput for an unsupported extension (loc.file = out_path), an unknown body
/// (with a "did you mean" suggestion), too many bodies, a size out of range or too small for
/// the layout, or an empty actual trajectory; ErrorKind::CannotCreate (loc.file = out_path)
/// when the file cannot be created; ErrorKind::IoError when writing it fails;
/// ErrorKind::Internal when cairo fails.
bool plotTrajectory(const Trajectory& actual, const Trajectory* golden, const PlotOptions& options,
                    const std::string& out_path, Error* err);

}  // namespace simbob
