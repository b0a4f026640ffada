// The gallery of a sweep (include/simbob/tool/replay_page.h, `sweep gather --html`): the gathered table as
// JSON in the page, drawn by the page's short script (lib/view/gallery.html, embedded at build
// time) -- a sortable table with a link to each case's replay page, and an SVG plot of one column
// against another.
#include <nlohmann/json.hpp>

#include "simbob/tool/replay_page.h"
#include "simbob/tool/test_report.h"
#include "simbob/values.h"
#include "view/assets.h"

namespace simbob {

std::string sweepGalleryHtml(const std::string& title, const std::vector<std::string>& columns,
                             const std::vector<GalleryCase>& cases) {
  nlohmann::json j;
  j["title"] = title;
  j["columns"] = columns;
  j["cases"] = nlohmann::json::array();
  for (const GalleryCase& c : cases)
    j["cases"].push_back({{"index", c.index},
                          {"status", c.status},
                          {"fields", c.fields},
                          {"page", c.page.empty() ? "" : relativeLink(c.page)}});
  return view::fill(view::kGalleryHtml,
                    {{"TITLE", escapeXml(title)},
                     {"DATA", view::scriptSafe(j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace))}});
}

}  // namespace simbob
