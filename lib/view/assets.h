// The page template and the viewer script (lib/view/page.html, lib/view/viewer.js), embedded at
// build time: CMake writes them into generated/view_assets.cpp as raw string literals.
#pragma once

namespace simbob::view {
extern const char* const kPageHtml;  ///< lib/view/page.html
extern const char* const kViewerJs;  ///< lib/view/viewer.js
}  // namespace simbob::view
