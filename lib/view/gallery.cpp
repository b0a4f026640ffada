// The gallery of a sweep (include/simbob/view.h, `sweep gather --html`): the gathered table as
// JSON in the page, drawn by a short script -- a sortable table with a link to each case's
// replay page, and an SVG plot of one column against another.
#include <nlohmann/json.hpp>

#include "simbob/view.h"

namespace simbob {

namespace {

std::string escapeText(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else
      out += c;
  }
  return out;
}

// The page: the data block, then the script that lays it out (kept here: it is short, and has
// no part in common with the replay viewer).
const char* const kGalleryHead = R"GALLERY(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="generator" content="simbob sweep gather --html">
<title>)GALLERY";

const char* const kGalleryBody = R"GALLERY(</title>
<style>
  body { font: 13px/1.4 system-ui, sans-serif; margin: 16px; color: #222; }
  table { border-collapse: collapse; margin-top: 12px; }
  th, td { border: 1px solid #ccc; padding: 2px 8px; text-align: right; font-family: monospace; }
  th { cursor: pointer; background: #eee; }
  th.sorted-up::after { content: " \25B2"; } th.sorted-down::after { content: " \25BC"; }
  tr.failed td { background: #fde2e2; } tr.missing td { background: #eee; color: #888; font-style: italic; }
  svg { border: 1px solid #ccc; background: #fff; }
</style>
</head>
<body>
<h1 id="title"></h1>
<p>Plot <select id="y"></select> against <select id="x"></select> (cases with status ok)</p>
<svg id="plot" width="640" height="320"></svg>
<table id="table"><thead></thead><tbody></tbody></table>
<script type="application/json" id="simbob-gallery">)GALLERY";

const char* const kGalleryScript = R"GALLERY(</script>
<script>
// simbob sweep gallery: a table of the gathered cases (click a heading to sort) with links to
// their replay pages, and a plot of one numeric column against another.
(function () {
  'use strict';
  const g = JSON.parse(document.getElementById('simbob-gallery').textContent);
  document.getElementById('title').textContent = g.title;
  const cols = g.columns;
  const head = document.querySelector('#table thead'), body = document.querySelector('#table tbody');
  const tr = document.createElement('tr');
  cols.concat(['page']).forEach((c, i) => {
    const th = document.createElement('th');
    th.textContent = c;
    if (i < cols.length) th.onclick = () => sortBy(i, th);
    tr.appendChild(th);
  });
  head.appendChild(tr);
  const rows = g.cases.map((c) => {
    const r = document.createElement('tr');
    r.className = c.status === 'ok' ? 'ok' : c.status === 'missing' ? 'missing' : 'failed';
    r.dataset.case = String(c.index);
    for (const f of c.fields) { const td = document.createElement('td'); td.textContent = f; r.appendChild(td); }
    const td = document.createElement('td');
    if (c.page) { const a = document.createElement('a'); a.href = c.page; a.textContent = 'view'; td.appendChild(a); } else td.textContent = c.status;
    r.appendChild(td);
    body.appendChild(r);
    return { el: r, c };
  });
  let sorted = -1, up = true;
  const num = (s) => (s === '' || isNaN(Number(s)) ? null : Number(s));
  function sortBy(i, th) {
    up = sorted === i ? !up : true;
    sorted = i;
    document.querySelectorAll('th').forEach((h) => h.classList.remove('sorted-up', 'sorted-down'));
    th.classList.add(up ? 'sorted-up' : 'sorted-down');
    rows.sort((a, b) => {
      const x = a.c.fields[i], y = b.c.fields[i], nx = num(x), ny = num(y);
      const d = nx !== null && ny !== null ? nx - ny : String(x).localeCompare(String(y));
      return up ? d : -d;
    });
    for (const r of rows) body.appendChild(r.el);
  }
  // The plot: numeric columns only; by default the first metric against the second column (the
  // first varied parameter after "case").
  const numeric = cols.map((c, i) => i).filter((i) => g.cases.some((c) => c.status === 'ok' && num(c.fields[i]) !== null));
  const xs = document.getElementById('x'), ys = document.getElementById('y');
  for (const i of numeric) { xs.add(new Option(cols[i], String(i))); ys.add(new Option(cols[i], String(i))); }
  if (numeric.length > 1) xs.value = String(numeric[1]);
  const firstMetric = cols.indexOf('wall_seconds') + 1;  // the metrics follow it
  if (numeric.length) ys.value = String(numeric.includes(firstMetric) ? firstMetric : numeric[numeric.length - 1]);
  xs.onchange = ys.onchange = plot;
  function plot() {
    const svg = document.getElementById('plot');
    while (svg.firstChild) svg.removeChild(svg.firstChild);
    const xi = Number(xs.value), yi = Number(ys.value);
    const pts = g.cases.filter((c) => c.status === 'ok' && num(c.fields[xi]) !== null && num(c.fields[yi]) !== null)
      .map((c) => [num(c.fields[xi]), num(c.fields[yi])]).sort((a, b) => a[0] - b[0]);
    if (!pts.length) return;
    const W = 640, H = 320, M = 48;
    const lo = [Math.min(...pts.map((p) => p[0])), Math.min(...pts.map((p) => p[1]))];
    const hi = [Math.max(...pts.map((p) => p[0])), Math.max(...pts.map((p) => p[1]))];
    const sx = (v) => M + (W - 2 * M) * (hi[0] > lo[0] ? (v - lo[0]) / (hi[0] - lo[0]) : 0.5);
    const sy = (v) => H - M + (2 * M - H) * (hi[1] > lo[1] ? (v - lo[1]) / (hi[1] - lo[1]) : 0.5);
    const add = (tag, attrs, text) => {
      const e = document.createElementNS('http://www.w3.org/2000/svg', tag);
      for (const k in attrs) e.setAttribute(k, attrs[k]);
      if (text !== undefined) e.textContent = text;
      svg.appendChild(e);
    };
    add('polyline', { points: pts.map((p) => sx(p[0]) + ',' + sy(p[1])).join(' '), fill: 'none', stroke: '#1f5fd6' });
    for (const p of pts) add('circle', { cx: sx(p[0]), cy: sy(p[1]), r: 3, fill: '#1f5fd6' });
    add('text', { x: W / 2, y: H - 8, 'text-anchor': 'middle' }, cols[xi] + ' (' + lo[0] + ' .. ' + hi[0] + ')');
    add('text', { x: 8, y: 16 }, cols[yi] + ' (' + lo[1] + ' .. ' + hi[1] + ')');
  }
  plot();
  window.simbobGallery = { ready: true, sortBy: (name) => sortBy(cols.indexOf(name), document.querySelectorAll('th')[cols.indexOf(name)]),
    order: () => rows.map((r) => r.c.index), points: () => document.querySelectorAll('#plot circle').length };
})();
</script>
</body>
</html>
)GALLERY";

}  // namespace

std::string sweepGalleryHtml(const std::string& title, const std::vector<std::string>& columns,
                             const std::vector<GalleryCase>& cases) {
  nlohmann::json j;
  j["title"] = title;
  j["columns"] = columns;
  j["cases"] = nlohmann::json::array();
  for (const GalleryCase& c : cases)
    j["cases"].push_back({{"index", c.index}, {"status", c.status}, {"fields", c.fields}, {"page", c.page}});
  std::string data = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  for (char c : data) safe += c == '<' ? std::string("\\u003c") : std::string(1, c);
  return std::string(kGalleryHead) + escapeText(title) + kGalleryBody + safe + kGalleryScript;
}

}  // namespace simbob
