// The cairo side of `simbob plot` (plot.cpp), built as a module of its own (libsimbob_plot.so)
// and opened by plot_loader.cpp on the first plot: a run that draws no plot does not load cairo
// and the X11, fontconfig and freetype libraries it brings. The program that opens it provides
// simbob's own functions the module calls (formatNumber, didYouMean, writeFileAtomically): it is
// linked with ENABLE_EXPORTS.
#pragma once

#include "simbob/tool/plot.h"

namespace simbob {

/// plotTrajectory itself, under another name (the program's plotTrajectory opens the module).
bool cairoPlotTrajectory(const Trajectory& actual, const Trajectory* golden, const PlotOptions& options,
                         const std::string& out_path, Error* err);

/// What simbob_plot_module() returns; `abi` is kPlotModuleAbi of the module's build.
struct PlotModule {
  int abi;
  bool (*plot)(const Trajectory& actual, const Trajectory* golden, const PlotOptions& options,
               const std::string& out_path, Error* err);
};
constexpr int kPlotModuleAbi = 1;

}  // namespace simbob

extern "C" const simbob::PlotModule* simbob_plot_module();
