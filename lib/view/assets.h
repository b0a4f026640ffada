// The page templates and the viewer script (lib/view/page.html, lib/view/viewer.js,
// lib/view/gallery.html), embedded at build time: CMake writes them into
// generated/view_assets.cpp as raw string literals. And the helpers that fill them in.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace simbob::view {
extern const char* const kPageHtml;     ///< lib/view/page.html
extern const char* const kViewerJs;     ///< lib/view/viewer.js
extern const char* const kGalleryHtml;  ///< lib/view/gallery.html

/// The template with each `{{NAME}}` marker replaced by its value (markers are looked for in the
/// template only, never in the values put in); a marker without a value stays as it is.
std::string fill(const std::string& page, const std::vector<std::pair<std::string, std::string>>& values);
/// Text for inside a <script> element: never "</script" nor "<!--" (every '<' as \u003c, which
/// JSON reads back as '<').
std::string scriptSafe(const std::string& s);
}  // namespace simbob::view
