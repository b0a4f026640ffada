// `simbob plot` and the failure plots of batch (include/simbob/tool/plot.h), drawn with cairo to
// PNG or SVG. Linked into the program (a module opened at run time until issue 44).
#include "simbob/tool/files.h"
#include "simbob/tool/plot.h"
#include "simbob/values.h"

#include <cairo-svg.h>
#include <cairo.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <unordered_map>
#include <array>
#include <vector>

namespace simbob {
namespace {

constexpr int kMinWidth = 200;
constexpr int kMinHeight = 300;
constexpr int kMaxSide = 10000;
constexpr int kPanelHeight = 300;  // default height per panel when PlotOptions::height == 0
constexpr int kPanels = 4;         // x, y, z and (PlotOptions::rotation) the rotation panel
constexpr int kRotation = 3;       // the component of the rotation panel

// Layout, in pixels.
constexpr double kOuterPad = 16;     // image edge to title / legend
constexpr double kMarginRight = 28;  // box right edge to image edge (room for the last label)
constexpr double kTitleSize = 17;    // font size of the headline
constexpr double kTextSize = 12;     // font size of labels and legend
constexpr double kPanelTitleSize = 13;
constexpr double kLegendRowH = 18;
constexpr double kLegendSwatch = 28;  // length of the line sample in a legend entry
constexpr double kPanelTitleH = 22;   // above each box
constexpr double kTickLabelH = 20;    // below each box
constexpr double kPanelGap = 8;       // between panels
constexpr double kFooterH = 28;       // "time [s]"
constexpr double kTickLen = 5;
constexpr double kLineWidth = 2.0;  // 2 px: a horizontal line always fully covers one row
constexpr double kGoldenWidth = 1.5;
constexpr double kDash[] = {7.0, 4.0};
constexpr size_t kMaxLabelChars = 48;  // body keys longer than this are shortened in the legend
constexpr double kMinBoxSide = 30;     // smallest usable panel box
constexpr double kPi = 3.14159265358979323846;

constexpr const char* kPanelTitles[kPanels] = {"x [m]", "y [m]", "z [m]", "rotation from the first orientation [rad]"};

enum class Format { Png, Svg };

struct Rect {
  double x = 0, y = 0, w = 0, h = 0;
};

/// A value range with its "nice" ticks.
struct Axis {
  double lo = 0, hi = 1;
  double step = 1;
  std::vector<double> ticks;
  std::vector<std::string> labels;
};

/// One plotted body: its index in the actual and (if any) the golden trajectory.
using Orientation = std::array<double, 4>;  // w x y z

struct Series {
  size_t actual = 0;
  size_t golden = SIZE_MAX;
  Orientation actual_first{1, 0, 0, 0};  // each trajectory's first orientation of the body
  Orientation golden_first{1, 0, 0, 0};
  PlotColor color;
  std::string label;
};

void setError(Error* err, ErrorKind kind, const std::string& file, std::string message) {
  if (!err) return;
  err->kind = kind;
  err->loc.file = file;
  err->loc.line = 0;
  err->message = std::move(message);
}

char lowerAscii(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

// "(did you mean 'k'?)" for a close key, else a short list of what exists.
std::string bodySuggestion(const std::string& wanted, const std::vector<std::string>& keys) {
  const std::string best = didYouMean(wanted, keys);
  if (!best.empty()) return " (did you mean '" + best + "'?)";
  std::string out = " (bodies: ";
  const size_t shown = std::min<size_t>(keys.size(), 5);
  for (size_t i = 0; i < shown; ++i) {
    if (i) out += ", ";
    out += keys[i];
  }
  if (keys.size() > shown) out += ", ...";
  return out + ")";
}

std::string lowerExtension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = lowerAscii(c);
  return ext;
}

// Valid UTF-8 without control characters: cairo's toy text API puts the context into an error
// state on invalid UTF-8, which would silently stop all further drawing.
std::string displayText(std::string_view s, size_t max_chars) {
  std::string out;
  size_t chars = 0;
  size_t i = 0;
  while (i < s.size()) {
    if (chars == max_chars) {
      out += "...";
      break;
    }
    const auto c = static_cast<unsigned char>(s[i]);
    size_t len = 0;
    uint32_t cp = 0;
    if (c < 0x80) {
      len = 1;
      cp = c;
    } else if ((c & 0xE0) == 0xC0) {
      len = 2;
      cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3;
      cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4;
      cp = c & 0x07;
    }
    bool ok = len > 0 && i + len <= s.size();
    for (size_t k = 1; ok && k < len; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      ok = (cc & 0xC0) == 0x80;
      cp = (cp << 6) | (cc & 0x3F);
    }
    static constexpr uint32_t kMinForLen[5] = {0, 0, 0x80, 0x800, 0x10000};
    ok = ok && cp >= kMinForLen[len] && cp <= 0x10FFFF && !(cp >= 0xD800 && cp <= 0xDFFF);
    if (!ok) {
      out += '?';
      i += 1;
    } else if (cp < 0x20 || cp == 0x7F) {
      out += '?';
      i += len;
    } else {
      out.append(s.data() + i, len);
      i += len;
    }
    ++chars;
  }
  return out;
}

// 1, 2 or 5 times a power of ten, the smallest such value >= raw.
double niceStep(double raw) {
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / base;
  const double m = f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0;
  return m * base;
}

std::string formatTick(double v, double step, double max_abs) {
  char buf[64];
  const int step_exp = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  if (max_abs >= 1e7 || step_exp < -6) {
    // Enough significant digits to tell neighbouring ticks apart.
    const int mag_exp = max_abs > 0 ? static_cast<int>(std::floor(std::log10(max_abs))) : step_exp;
    const int digits = std::clamp(mag_exp - step_exp + 1, 1, 17);
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  } else {
    std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -step_exp), v);
  }
  return buf;
}

/// Ticks for [lo, hi] drawn over `pixels`, about one per `px_per_tick`.
Axis makeAxis(double lo, double hi, double pixels, double px_per_tick) {
  Axis a;
  a.lo = lo;
  a.hi = hi;
  const double target = std::max(2.0, std::floor(pixels / px_per_tick));
  a.step = niceStep((hi - lo) / target);
  const double k0 = std::ceil(lo / a.step - 1e-9);
  const double k1 = std::floor(hi / a.step + 1e-9);
  for (double k = k0; k <= k1 && a.ticks.size() < 100; k += 1.0) {
    double v = k * a.step;
    if (std::fabs(v) < a.step * 1e-9) v = 0.0;  // never print "-0"
    a.ticks.push_back(v);
  }
  double max_abs = 0;
  for (double v : a.ticks) max_abs = std::max(max_abs, std::fabs(v));
  for (double v : a.ticks) a.labels.push_back(formatTick(v, a.step, max_abs));
  return a;
}

/// A constant (or empty) range gets room around it; a real one 5% padding per side.
void padRange(double* lo, double* hi, double pad_fraction) {
  if (*lo > *hi) {  // no data at all
    *lo = -1.0;
    *hi = 1.0;
    return;
  }
  const double mag = std::max({1.0, std::fabs(*lo), std::fabs(*hi)});
  if (*hi - *lo <= 1e-12 * mag) {
    const double c = 0.5 * (*lo + *hi);
    const double half = std::max(0.5, std::fabs(c) * 0.1);
    *lo = c - half;
    *hi = c + half;
    return;
  }
  const double pad = (*hi - *lo) * pad_fraction;
  *lo -= pad;
  *hi += pad;
}

void setColor(cairo_t* cr, PlotColor c) { cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0); }

void setGray(cairo_t* cr, double v) { cairo_set_source_rgb(cr, v, v, v); }

void setFont(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double textWidth(cairo_t* cr, const std::string& s) {
  cairo_text_extents_t ext;
  cairo_text_extents(cr, s.c_str(), &ext);
  return ext.x_advance;
}

/// Draws s with its baseline at y; align 0 = left, 0.5 = centre, 1 = right of x.
void drawText(cairo_t* cr, const std::string& s, double x, double y, double align) {
  cairo_move_to(cr, x - align * textWidth(cr, s), y);
  cairo_show_text(cr, s.c_str());
}

/// Maps data to device coordinates inside one panel box.
struct Mapper {
  Rect box;
  double t0 = 0, t1 = 1, v0 = 0, v1 = 1;
  double x(double t) const { return box.x + (t - t0) / (t1 - t0) * box.w; }
  double y(double v) const { return box.y + box.h - (v - v0) / (v1 - v0) * box.h; }
};

/// Pixel column of every sample time: the unit of decimation.
std::vector<int32_t> sampleColumns(const Trajectory& tr, double t0, double t1, double width) {
  std::vector<int32_t> cols(tr.times.size());
  const double max_col = std::max(0.0, std::ceil(width) - 1);
  for (size_t s = 0; s < tr.times.size(); ++s) {
    const double c = std::floor((tr.times[s] - t0) / (t1 - t0) * width);
    cols[s] = static_cast<int32_t>(std::clamp(c, 0.0, max_col));
  }
  return cols;
}

/// The angle (rad, 0..pi) of the rotation from `first` to the orientation of row p (x y z w x y z):
/// 2 atan2(|v|, |w|) of first^-1 * q, accurate for small angles too.
double rotationFrom(const Orientation& first, const double* p) {
  const double aw = first[0], ax = -first[1], ay = -first[2], az = -first[3];
  const double bw = p[3], bx = p[4], by = p[5], bz = p[6];
  const double w = aw * bw - ax * bx - ay * by - az * bz;
  const double x = aw * bx + ax * bw + ay * bz - az * by;
  const double y = aw * by - ax * bz + ay * bw + az * bx;
  const double z = aw * bz + ax * by - ay * bx + az * bw;
  return 2 * std::atan2(std::sqrt(x * x + y * y + z * z), std::fabs(w));
}

/// Component comp of a row: x, y, z, or (kRotation) the rotation from `first`.
double componentOf(const double* p, int comp, const Orientation& first) {
  return comp == kRotation ? rotationFrom(first, p) : p[comp];
}

/// The first orientation of body b in tr (identity when it has no row).
Orientation firstOrientation(const Trajectory& tr, size_t b) {
  for (size_t s = 0; s < tr.times.size(); ++s)
    if (const double* p = tr.pose(s, b)) return {p[3], p[4], p[5], p[6]};
  return {1, 0, 0, 0};
}

/// Adds one component of one body as sub-paths (a break at every missing row), keeping per pixel
/// column only the first, lowest, highest and last sample so long trajectories stay cheap to
/// draw while spikes survive. Isolated samples are collected in `dots`.
void addSeriesPath(cairo_t* cr, const Trajectory& tr, size_t body, int comp, const Orientation& from,
                   const std::vector<int32_t>& cols, const Mapper& m, std::vector<size_t>* run,
                   std::vector<size_t>* dots) {
  run->clear();
  bool open = false;  // a column bucket is being filled
  int32_t col = 0;
  size_t first = 0, last = 0, lo = 0, hi = 0;
  double lo_v = 0, hi_v = 0;

  auto flushBucket = [&]() {
    if (!open) return;
    size_t picks[4] = {first, lo, hi, last};
    std::sort(picks, picks + 4);
    for (size_t p : picks) {
      if (run->empty() || run->back() != p) run->push_back(p);
    }
    open = false;
  };
  auto emitRun = [&]() {
    flushBucket();
    if (run->size() == 1) {
      dots->push_back(run->front());
    } else if (run->size() > 1) {
      for (size_t i = 0; i < run->size(); ++i) {
        const size_t s = (*run)[i];
        const double px = m.x(tr.times[s]);
        const double py = m.y(componentOf(tr.pose(s, body), comp, from));
        if (i == 0) {
          cairo_move_to(cr, px, py);
        } else {
          cairo_line_to(cr, px, py);
        }
      }
    }
    run->clear();
  };

  for (size_t s = 0; s < tr.times.size(); ++s) {
    const double* p = tr.pose(s, body);
    if (!p) {
      emitRun();
      continue;
    }
    const double v = componentOf(p, comp, from);
    if (!open || cols[s] != col) {
      flushBucket();
      open = true;
      col = cols[s];
      first = last = lo = hi = s;
      lo_v = hi_v = v;
      continue;
    }
    last = s;
    if (v < lo_v) {
      lo_v = v;
      lo = s;
    }
    if (v > hi_v) {
      hi_v = v;
      hi = s;
    }
  }
  emitRun();
}

/// Strokes one series (solid or dashed) and marks its isolated samples with dots.
void drawSeries(cairo_t* cr, const Trajectory& tr, size_t body, int comp, const Orientation& first,
                const std::vector<int32_t>& cols, const Mapper& m, PlotColor color, bool dashed,
                std::vector<size_t>* run) {
  std::vector<size_t> dots;
  cairo_new_path(cr);
  addSeriesPath(cr, tr, body, comp, first, cols, m, run, &dots);
  setColor(cr, color);
  cairo_set_line_width(cr, dashed ? kGoldenWidth : kLineWidth);
  if (dashed) cairo_set_dash(cr, kDash, 2, 0);
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0);
  for (size_t s : dots) {
    const double r = dashed ? 2.5 : 3.0;
    cairo_new_sub_path(cr);
    cairo_arc(cr, m.x(tr.times[s]), m.y(componentOf(tr.pose(s, body), comp, first)), r, 0, 2 * kPi);
  }
  cairo_fill(cr);
}

void drawLegendSwatch(cairo_t* cr, double x, double y, PlotColor color, bool dashed) {
  cairo_new_path(cr);
  cairo_move_to(cr, x, y);
  cairo_line_to(cr, x + kLegendSwatch, y);
  setColor(cr, color);
  cairo_set_line_width(cr, dashed ? kGoldenWidth : kLineWidth);
  if (dashed) cairo_set_dash(cr, kDash, 2, 0);
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0);
}

struct LegendItem {
  std::string label;
  PlotColor color;
  bool dashed = false;
};

/// Everything needed to draw, computed before any drawing.
struct Scene {
  const Trajectory* actual = nullptr;
  const Trajectory* golden = nullptr;
  std::vector<Series> series;
  std::string title;
  double t_lo = 0, t_hi = 1;
  double v_lo[kPanels] = {0, 0, 0, 0};
  double v_hi[kPanels] = {0, 0, 0, 0};
  int panels = 3;
  int comps[kPanels] = {0, 1, 2, kRotation};  // the component each panel shows
  std::string titles[kPanels] = {kPanelTitles[0], kPanelTitles[1], kPanelTitles[2], kPanelTitles[3]};
  std::string time_label = "time [s]";
};

/// Paints the background and draws the headline and the legend (wrapped into rows); returns
/// where the panels start.
double drawHeader(cairo_t* cr, const Scene& sc, double width) {
  cairo_font_options_t* fo = cairo_font_options_create();
  // Unhinted grey-scale text: identical metrics on every surface type and display setting.
  cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
  cairo_set_font_options(cr, fo);
  cairo_font_options_destroy(fo);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);

  setGray(cr, 1.0);
  cairo_paint(cr);

  // Headline.
  double y = kOuterPad;
  setFont(cr, kTitleSize, true);
  setGray(cr, 0.1);
  drawText(cr, sc.title, kOuterPad, y + kTitleSize, 0);
  y += kTitleSize + 10;

  // Legend, wrapped into rows.
  std::vector<LegendItem> items;
  for (const Series& s : sc.series) items.push_back({s.label, s.color, false});
  if (sc.golden) items.push_back({"golden", PlotColor{90, 90, 90}, true});
  setFont(cr, kTextSize, false);
  double lx = kOuterPad;
  double row_y = y + kLegendRowH * 0.5;
  for (const LegendItem& it : items) {
    const double w = kLegendSwatch + 6 + textWidth(cr, it.label);
    if (lx > kOuterPad && lx + w > width - kOuterPad) {
      lx = kOuterPad;
      row_y += kLegendRowH;
    }
    drawLegendSwatch(cr, lx, row_y, it.color, it.dashed);
    setGray(cr, 0.1);
    drawText(cr, it.label, lx + kLegendSwatch + 6, row_y + kTextSize * 0.35, 0);
    lx += w + 20;
  }
  return row_y + kLegendRowH * 0.5 + 6;
}

/// The sampled columns of the actual and golden trajectories, and a scratch run of indices.
struct Columns {
  std::vector<int32_t> actual, golden;
  std::vector<size_t> run;
};

/// Panel p in the box of `m`: title, grid, data (golden under actual), frame, ticks, labels.
void drawPanel(cairo_t* cr, const Scene& sc, int p, const Mapper& m, const Axis& taxis, const Axis& vaxis,
               Columns* cols) {
  const Rect& b = m.box;
  setFont(cr, kPanelTitleSize, true);
  setGray(cr, 0.1);
  drawText(cr, sc.titles[p], b.x, b.y - 7, 0);

  // Grid (half-pixel offsets keep 1 px lines crisp).
  cairo_set_line_width(cr, 1.0);
  setGray(cr, 0.9);
  for (double t : taxis.ticks) {
    const double px = std::round(m.x(t)) + 0.5;
    cairo_move_to(cr, px, b.y);
    cairo_line_to(cr, px, b.y + b.h);
  }
  for (double v : vaxis.ticks) {
    const double py = std::round(m.y(v)) + 0.5;
    cairo_move_to(cr, b.x, py);
    cairo_line_to(cr, b.x + b.w, py);
  }
  cairo_stroke(cr);

  // Data, clipped to the box; golden first so the actual lines stay on top.
  cairo_save(cr);
  cairo_rectangle(cr, b.x, b.y, b.w, b.h);
  cairo_clip(cr);
  if (sc.golden) {
    for (const Series& s : sc.series) {
      if (s.golden == SIZE_MAX) continue;
      drawSeries(cr, *sc.golden, s.golden, sc.comps[p], s.golden_first, cols->golden, m, s.color, true, &cols->run);
    }
  }
  for (const Series& s : sc.series) {
    drawSeries(cr, *sc.actual, s.actual, sc.comps[p], s.actual_first, cols->actual, m, s.color, false, &cols->run);
  }
  cairo_restore(cr);

  // Frame and ticks.
  cairo_set_line_width(cr, 1.0);
  setGray(cr, 0.25);
  cairo_rectangle(cr, b.x + 0.5, b.y + 0.5, b.w - 1, b.h - 1);
  for (double t : taxis.ticks) {
    const double px = std::round(m.x(t)) + 0.5;
    cairo_move_to(cr, px, b.y + b.h);
    cairo_line_to(cr, px, b.y + b.h + kTickLen);
  }
  for (double v : vaxis.ticks) {
    const double py = std::round(m.y(v)) + 0.5;
    cairo_move_to(cr, b.x - kTickLen, py);
    cairo_line_to(cr, b.x, py);
  }
  cairo_stroke(cr);

  setFont(cr, kTextSize, false);
  setGray(cr, 0.2);
  for (size_t i = 0; i < taxis.ticks.size(); ++i) {
    drawText(cr, taxis.labels[i], m.x(taxis.ticks[i]), b.y + b.h + kTickLen + kTextSize + 1, 0.5);
  }
  for (size_t i = 0; i < vaxis.ticks.size(); ++i) {
    drawText(cr, vaxis.labels[i], b.x - kTickLen - 4, m.y(vaxis.ticks[i]) + kTextSize * 0.35, 1.0);
  }
}

/// Lays out and draws everything; returns why the image is too small for the layout, else "".
std::string render(cairo_t* cr, const Scene& sc, double width, double height) {
  const double panels_top = drawHeader(cr, sc, width);
  const double slot_h = (height - kFooterH - panels_top) / sc.panels;
  const double box_h = slot_h - kPanelTitleH - kTickLabelH - kPanelGap;
  if (box_h < kMinBoxSide) {
    return "plot height " + std::to_string(static_cast<int>(height)) +
           " px is too small for three panels and the legend";
  }

  // Value axes first: their widest label decides the left margin.
  Axis vaxes[kPanels];
  double label_w = 0;
  for (int p = 0; p < sc.panels; ++p) {
    vaxes[p] = makeAxis(sc.v_lo[p], sc.v_hi[p], box_h, 40);
    for (const std::string& l : vaxes[p].labels) label_w = std::max(label_w, textWidth(cr, l));
  }
  const double box_x = std::floor(std::max(50.0, label_w + kTickLen + 12));
  const double box_w = std::floor(width - kMarginRight - box_x);
  if (box_w < kMinBoxSide) {
    return "plot width " + std::to_string(static_cast<int>(width)) + " px is too small for the axis labels";
  }
  const Axis taxis = makeAxis(sc.t_lo, sc.t_hi, box_w, 90);

  Columns cols;
  cols.actual = sampleColumns(*sc.actual, sc.t_lo, sc.t_hi, box_w);
  if (sc.golden) cols.golden = sampleColumns(*sc.golden, sc.t_lo, sc.t_hi, box_w);
  for (int p = 0; p < sc.panels; ++p) {
    const double slot_y = panels_top + p * slot_h;
    Mapper m;
    m.box = Rect{box_x, std::floor(slot_y + kPanelTitleH), box_w, std::floor(box_h)};
    m.t0 = sc.t_lo;
    m.t1 = sc.t_hi;
    m.v0 = vaxes[p].lo;
    m.v1 = vaxes[p].hi;
    drawPanel(cr, sc, p, m, taxis, vaxes[p], &cols);
  }

  setFont(cr, kTextSize, true);
  setGray(cr, 0.1);
  drawText(cr, sc.time_label, box_x + box_w * 0.5, height - 9, 0.5);
  return "";
}

/// cairo names SVG groups after a process-wide surface counter ("surface93"); renumbering them
/// in order of appearance makes the same plot produce the same SVG bytes in any process.
std::string normalizeSvgIds(const std::string& svg) {
  static constexpr std::string_view kWord = "surface";
  std::unordered_map<std::string, size_t> ids;
  std::string out;
  out.reserve(svg.size());
  size_t i = 0;
  while (i < svg.size()) {
    const size_t hit = svg.find(kWord, i);
    if (hit == std::string::npos) break;
    size_t end = hit + kWord.size();
    while (end < svg.size() && svg[end] >= '0' && svg[end] <= '9') ++end;
    const bool is_ref = hit > 0 && (svg[hit - 1] == '"' || svg[hit - 1] == '#');
    out.append(svg, i, hit - i);
    if (is_ref && end > hit + kWord.size()) {
      const auto it = ids.emplace(svg.substr(hit, end - hit), ids.size() + 1).first;
      out += kWord;
      out += std::to_string(it->second);
    } else {
      out.append(svg, hit, end - hit);
    }
    i = end;
  }
  out.append(svg, i, std::string::npos);
  return out;
}

cairo_status_t appendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

/// Renders to PNG or SVG bytes. On failure returns "" and sets *why and *kind (InvalidInput
/// when the layout does not fit, Internal when cairo fails).
std::string renderToBytes(const Scene& sc, Format format, int width, int height, std::string* why, ErrorKind* kind) {
  std::string bytes;
  cairo_surface_t* surface = format == Format::Png
                                 ? cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)
                                 : cairo_svg_surface_create_for_stream(appendToString, &bytes, width, height);
  if (format == Format::Svg) cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
  cairo_t* cr = cairo_create(surface);
  const std::string layout_problem = render(cr, sc, width, height);
  cairo_status_t st = cairo_status(cr);
  cairo_destroy(cr);
  if (!layout_problem.empty()) {
    cairo_surface_destroy(surface);
    *why = layout_problem;
    *kind = ErrorKind::InvalidInput;
    return {};
  }
  if (st == CAIRO_STATUS_SUCCESS) {
    if (format == Format::Png) {
      cairo_surface_flush(surface);
      st = cairo_surface_write_to_png_stream(surface, appendToString, &bytes);
    } else {
      cairo_surface_finish(surface);  // the SVG stream is written here
      st = cairo_surface_status(surface);
    }
  }
  cairo_surface_destroy(surface);
  if (st != CAIRO_STATUS_SUCCESS) {
    *why = std::string("cannot render plot: cairo: ") + cairo_status_to_string(st);
    *kind = ErrorKind::Internal;
    return {};
  }
  return format == Format::Svg ? normalizeSvgIds(bytes) : bytes;
}

/// Extends [lo, hi] of each component by body b's rows in tr.
void extendRanges(const Trajectory& tr, size_t b, const Orientation& first, double* lo, double* hi) {
  for (size_t s = 0; s < tr.times.size(); ++s) {
    const double* p = tr.pose(s, b);
    if (!p) continue;
    for (int c = 0; c < kPanels; ++c) {
      const double v = componentOf(p, c, first);
      lo[c] = std::min(lo[c], v);
      hi[c] = std::max(hi[c], v);
    }
  }
}

std::unordered_map<std::string, size_t> bodyIndex(const Trajectory& tr) {
  std::unordered_map<std::string, size_t> index;
  for (size_t b = 0; b < tr.bodies.size(); ++b) index.emplace(tr.bodies[b], b);  // first wins
  return index;
}

}  // namespace

namespace {

/// The bodies to plot, in legend order: those named (at most kMaxPlotBodies), or the first
/// kMaxPlotBodies (saying so in `note`). False and *err for a name the trajectory lacks.
bool selectBodies(const Trajectory& actual, const PlotOptions& options, std::vector<size_t>* selected,
                  std::string* note, Error* err) {
  if (options.bodies.empty()) {
    const size_t n = std::min(actual.bodyCount(), kMaxPlotBodies);
    for (size_t b = 0; b < n; ++b) selected->push_back(b);
    if (actual.bodyCount() > n) {
      *note = " (first " + std::to_string(n) + " of " + std::to_string(actual.bodyCount()) + " bodies)";
    }
    return true;
  }
  const auto index = bodyIndex(actual);
  for (const std::string& key : options.bodies) {
    const auto it = index.find(key);
    if (it == index.end()) {
      setError(err, ErrorKind::InvalidInput, "",
               "no body '" + key + "' in trajectory" + bodySuggestion(key, actual.bodies));
      return false;
    }
    if (std::find(selected->begin(), selected->end(), it->second) == selected->end()) {
      selected->push_back(it->second);
    }
  }
  if (selected->size() > kMaxPlotBodies) {
    setError(err, ErrorKind::InvalidInput, "",
             "too many bodies for one plot: " + std::to_string(selected->size()) + " (at most " +
                 std::to_string(kMaxPlotBodies) + ")");
    return false;
  }
  return true;
}

}  // namespace

bool plotTrajectory(const Trajectory& actual, const Trajectory* golden, const PlotOptions& options,
                    const std::string& out_path, Error* err) {
  const std::string ext = lowerExtension(out_path);
  Format format;
  if (ext == ".png") {
    format = Format::Png;
  } else if (ext == ".svg") {
    format = Format::Svg;
  } else {
    setError(err, ErrorKind::InvalidInput, out_path,
             "unsupported plot format " + (ext.empty() ? std::string("(no extension)") : "'" + ext + "'") +
                 " (use .png or .svg)");
    return false;
  }

  const int width = options.width;
  if (options.panels < 1 || options.panels > 3) {
    setError(err, ErrorKind::InvalidInput, "", "plot panels must be 1 to 3");
    return false;
  }
  const int panels = options.panels + (options.rotation ? 1 : 0);
  const int height = options.height == 0 ? kPanelHeight * panels : options.height;
  if (width < kMinWidth || width > kMaxSide || height < kMinHeight || height > kMaxSide) {
    setError(err, ErrorKind::InvalidInput, "",
             "plot size " + std::to_string(width) + "x" + std::to_string(height) + " out of range (width " +
                 std::to_string(kMinWidth) + ".." + std::to_string(kMaxSide) + ", height " +
                 std::to_string(kMinHeight) + ".." + std::to_string(kMaxSide) + " px)");
    return false;
  }
  if (actual.sampleCount() == 0 || actual.bodyCount() == 0) {
    setError(err, ErrorKind::InvalidInput, "", "nothing to plot: the trajectory is empty");
    return false;
  }

  // Which bodies, in legend order.
  std::vector<size_t> selected;
  std::string note;
  if (!selectBodies(actual, options, &selected, &note, err)) return false;

  Scene sc;
  sc.actual = &actual;
  sc.golden = (golden && golden->sampleCount() > 0) ? golden : nullptr;
  sc.title = displayText(options.title.empty() ? "trajectory" : options.title, 200) + note;
  sc.panels = panels;
  for (size_t p = 0; p < options.panel_titles.size() && p < 3; ++p)
    sc.titles[p] = displayText(options.panel_titles[p], kMaxLabelChars);
  if (options.rotation) {  // after the position panels
    sc.comps[options.panels] = kRotation;
    sc.titles[options.panels] = kPanelTitles[kRotation];
  }
  if (!options.time_label.empty()) sc.time_label = displayText(options.time_label, kMaxLabelChars);
  std::unordered_map<std::string, size_t> golden_index;
  if (sc.golden) golden_index = bodyIndex(*golden);
  double lo[kPanels], hi[kPanels];
  std::fill(lo, lo + kPanels, HUGE_VAL);
  std::fill(hi, hi + kPanels, -HUGE_VAL);
  for (size_t i = 0; i < selected.size(); ++i) {
    Series s;
    s.actual = selected[i];
    s.color = plotColor(i);
    s.label = displayText(actual.bodies[s.actual], kMaxLabelChars);
    s.actual_first = firstOrientation(actual, s.actual);
    extendRanges(actual, s.actual, s.actual_first, lo, hi);
    if (sc.golden) {
      const auto it = golden_index.find(actual.bodies[s.actual]);
      if (it != golden_index.end()) {
        s.golden = it->second;
        s.golden_first = firstOrientation(*golden, s.golden);
        extendRanges(*golden, s.golden, s.golden_first, lo, hi);
      } else {
        s.label += " (no golden)";
      }
    }
    sc.series.push_back(std::move(s));
  }
  // Beyond this an axis cannot span the data (hi - lo, the padding and the ticks overflow): say
  // so rather than draw an empty panel.
  constexpr double kMaxPlotMagnitude = 1e300;
  const char* const names[kPanels] = {"x", "y", "z", "rotation"};
  for (int p = 0; p < sc.panels; ++p)
    if (const int c = sc.comps[p]; std::fabs(lo[c]) > kMaxPlotMagnitude || std::fabs(hi[c]) > kMaxPlotMagnitude) {
      setError(err, ErrorKind::InvalidInput, "",
               std::string("cannot plot ") + names[c] + " values from " + formatNumber(lo[c]) + " to " +
                   formatNumber(hi[c]) + ": a plot axis spans at most -1e300 to 1e300");
      return false;
    }
  const double t_first = std::min(actual.times.front(), sc.golden ? sc.golden->times.front() : HUGE_VAL);
  const double t_last = std::max(actual.times.back(), sc.golden ? sc.golden->times.back() : -HUGE_VAL);
  if (std::fabs(t_first) > kMaxPlotMagnitude || std::fabs(t_last) > kMaxPlotMagnitude) {
    setError(err, ErrorKind::InvalidInput, "",
             "cannot plot times from " + formatNumber(t_first) + " to " + formatNumber(t_last) +
                 ": a plot axis spans at most -1e300 to 1e300");
    return false;
  }
  for (int p = 0; p < sc.panels; ++p) {
    const int c = sc.comps[p];
    padRange(&lo[c], &hi[c], 0.05);
    sc.v_lo[p] = lo[c];
    sc.v_hi[p] = hi[c];
  }
  // Time spans both trajectories (times are increasing, so the ends suffice).
  sc.t_lo = actual.times.front();
  sc.t_hi = actual.times.back();
  if (sc.golden) {
    sc.t_lo = std::min(sc.t_lo, sc.golden->times.front());
    sc.t_hi = std::max(sc.t_hi, sc.golden->times.back());
  }
  padRange(&sc.t_lo, &sc.t_hi, 0.0);

  std::string why;
  ErrorKind kind = ErrorKind::Internal;
  const std::string bytes = renderToBytes(sc, format, width, height, &why, &kind);
  if (bytes.empty()) {
    setError(err, kind, "", why);
    return false;
  }
  return writeFileAtomically(out_path, bytes, err);
}

}  // namespace simbob
