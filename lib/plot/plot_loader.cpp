// plotTrajectory opens libsimbob_plot.so (cairo, plot.cpp) the first time it is called; see
// plot_module.h. SIMBOB_PLOT_MODULE names the file explicitly.

#include "plot/plot_module.h"
#include "simbob/tool/platform.h"

namespace simbob {

bool plotTrajectory(const Trajectory& actual, const Trajectory* golden, const PlotOptions& options,
                    const std::string& out_path, Error* err) {
  std::string error;
  const PlotModule* module =
      simbobModule<PlotModule>("libsimbob_plot.so", "SIMBOB_PLOT_MODULE", "simbob_plot_module", kPlotModuleAbi,
                               "plotting needs libsimbob_plot.so (cairo)", nullptr, &error);
  if (!module) {
    if (err) *err = Error{ErrorKind::MissingInput, {out_path}, error};
    return false;
  }
  return module->plot(actual, golden, options, out_path, err);
}

}  // namespace simbob
