// The replay page (issue #23, `simbob view`): one self-contained HTML file that shows a
// trajectory in the scene it was run in -- the compiled Model the renderer draws from, the poses
// of the CSV, optionally a golden run as ghosts with the first divergence `simbob compare`
// reports. three.js is read from Debian's libjs-three when the page is written and inlined;
// nothing is fetched when the page is opened. docs/view.md describes the page and its data.
#pragma once

#include <string>
#include <vector>

#include "simbob/tool/comparison.h"
#include "simbob/error.h"
#include "simbob/model.h"
#include "simbob/trajectory.h"

namespace simbob {

/// Where three.min.js and examples/js/controls/OrbitControls.js are read from: $SIMBOB_THREE_DIR
/// when set, else Debian's /usr/share/javascript/three.
std::string threeJsDir();

struct ViewPageInput {
  const Model* model = nullptr;        ///< the scene as compiled (visuals, skins, cameras, geoms)
  const Trajectory* actual = nullptr;  ///< the run shown
  const Trajectory* golden = nullptr;  ///< optional: drawn as ghosts, compared
  CompareOptions compare;              ///< tolerances of the comparison with `golden`
  std::string title;                   ///< the page's title ("" = "simbob view")
  std::string texture_folder;          ///< global setting TextureFolder, searched before the scene's folder
  std::string scene_name;              ///< shown on the page (the scene path as given)
};

/// The decoded texture images a page embeds together (RGB, 3 bytes a pixel, each file once): a
/// browser holds each of them decoded, and the page their PNG in base64.
constexpr size_t kMaxPageTextureBytes = size_t{256} << 20;

/// What `check` says of a scene's textures before anything reads them whole: from each file's
/// header, a warning at the skin whose texture takes the scene's textures (each file once) past
/// kMaxPageTextureBytes (view and --html would refuse it), or past the renderer's budget.
void checkTextureBudgets(const Model& m, const std::string& texture_folder, Diagnostics& d);

/// The mesh data a page embeds together (base64 characters of float32 positions and uint32
/// indices, each mesh once): beyond it a browser takes seconds to parse the page (docs/meshes.md).
constexpr size_t kMaxPageMeshChars = size_t{64} << 20;

/// What `check` says of a scene's meshes: a warning where the first use of the mesh that takes
/// the page's mesh data past kMaxPageMeshChars is written (view and --html would refuse it),
/// counted as the page counts it.
void checkMeshBudget(const Model& m, Diagnostics& d);

/// Builds the page's HTML. Each texture file is embedded once, as the renderer reads it
/// (decoded, then as PNG), within kMaxPageTextureBytes. Errors: MissingInput when three.js or a
/// texture file cannot be found (naming the file and, for three.js, the package), InvalidInput
/// when a texture cannot be read (the reader's reason) or the textures exceed the budget.
bool buildViewPage(const ViewPageInput& in, std::string* html, Error* err);

/// buildViewPage, written to `path` as an OutputFile: an existing file is replaced only when the
/// whole page was written (CannotCreate / IoError otherwise, the old file left as it was).
bool writeViewPage(const ViewPageInput& in, const std::string& path, Error* err);

}  // namespace simbob

namespace simbob {

/// One row of a sweep's gallery (`sweep gather --html`).
struct GalleryCase {
  int index = 0;
  std::string status;               ///< "ok", "failed", "missing", ...
  std::vector<std::string> fields;  ///< the gathered table's cells of this case, in column order
  std::string page;                 ///< link to the case's replay page, relative to the gallery ("" = none)
};

/// The gallery page of a sweep: the gathered table (click a heading to sort), a plot of a chosen
/// metric against a chosen column, and a link to each case's page; failed and missing cases
/// marked. Self-contained (no three.js: plain HTML, SVG and a little script).
std::string sweepGalleryHtml(const std::string& title, const std::vector<std::string>& columns,
                             const std::vector<GalleryCase>& cases);

}  // namespace simbob
