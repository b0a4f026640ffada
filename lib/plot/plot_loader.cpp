// plotTrajectory opens libsimbob_plot.so (cairo, plot.cpp) the first time it is called; see
// plot_module.h. SIMBOB_PLOT_MODULE names the file explicitly.
#include <mutex>

#include "plot/plot_module.h"
#include "simbob/tool/platform.h"

namespace simbob {

bool plotTrajectory(const Trajectory& actual, const Trajectory* golden, const PlotOptions& options,
                    const std::string& out_path, Error* err) {
  static std::once_flag once;
  static const PlotModule* module = nullptr;
  static std::string error;
  std::call_once(once, [] {
    std::string not_found;
    const auto* m =
        openModuleTable<PlotModule>("libsimbob_plot.so", "SIMBOB_PLOT_MODULE", "simbob_plot_module", &not_found);
    if (!m)
      error = "plotting needs libsimbob_plot.so (cairo): " + not_found;
    else if (m->abi != kPlotModuleAbi)
      error = "libsimbob_plot.so is not this build's plot module (of another ABI)";
    else
      module = m;
  });
  if (!module) {
    if (err) *err = Error{ErrorKind::MissingInput, {out_path}, error};
    return false;
  }
  return module->plot(actual, golden, options, out_path, err);
}

}  // namespace simbob
