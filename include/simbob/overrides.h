// Overrides of scene parameters from the command line: `--set KEY.PARAM=VALUE`. They change the
// component graph after loading and before compiling, and read their values with the scene
// file's parser (parseParam), so a value means the same in a file and on the command line.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "simbob/error.h"
#include "simbob/graph.h"

namespace simbob {

/// One `KEY.PARAM=VALUE`. KEY is a fully qualified component key (docs/scene-format.md, "Conventions"; as
/// `simbob dump` and the CSV show it), PARAM the name of one of its value parameters.
struct Override {
  std::string text;   ///< as given, "Crate.Material.Friction=0.3"
  std::string key;    ///< "Crate.Material"
  std::string param;  ///< "Friction"
  std::string value;  ///< "0.3" (guide 4.3 syntax, as in the file)
  /// Where messages about it point: "--set Crate.Material.Friction=abc" (parseOverride), or
  /// the shorthand it stands for ("--space sap").
  std::string place;
  int line = 0;  ///< line in place when that is a file (a DocumentIni), else 0
  /// Only a camera's parameters may be set (DocumentIni, guide 3.3.1).
  bool cameras_only = false;
};

/// Splits `KEY.PARAM=VALUE` at the first '=' and the last '.' before it. Returns false with a
/// message ("expected KEY.PARAM=VALUE ...") when a part is missing.
bool parseOverride(std::string_view text, Override* out, std::string* error);

/// Applies the overrides in order to a loaded scene. An unknown key or parameter (with the
/// nearest as "did you mean"), a component-valued parameter or a value the parameter does not
/// take is an error in diag, placed at the override (`--set X.Y=Z: error: ...`). A KEY that
/// goes through a Ref or a left-out default component (`Crate.Material` where the file gave
/// none) reaches the component the body uses: a Ref's target (which all its users share), or a
/// private copy of the default (the other users keep theirs). Returns diag.ok().
bool applyOverrides(Scene& scene, const std::vector<Override>& overrides, Diagnostics& diag);

}  // namespace simbob
