#include "report/svg_chart.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>
#include <string>

namespace j232::report {

const std::string& palette(std::size_t i) {
  static const std::vector<std::string> colours = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"};
  return colours[i % colours.size()];
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) hi = lo + 1;
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::floor(lo / step) * step; t <= hi + 1e-9 * step; t += step) ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  if (ticks.empty() || ticks.front() > lo) ticks.insert(ticks.begin(), ticks.empty() ? lo : ticks.front() - step);
  if (ticks.back() < hi - 1e-9 * step) ticks.push_back(ticks.back() + step);
  return ticks;
}

std::string escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default:
        // Control characters (NUL, ESC ...) are not text: HTML forbids them and a page would
        // carry them raw. Shown as U+FFFD; tab and line ends kept.
        if ((static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
          out += "\xEF\xBF\xBD";
        else
          out += c;
    }
  return out;
}

namespace {

constexpr double kLeft = 72, kRight = 18, kTop = 34, kBottom = 48, kLegendRow = 17;

std::string tick_label(double v, double step) {
  const int decimals = std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 6);
  std::string s = fmt::format("{:.{}f}", v, decimals);
  if (s.front() == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);  // no "-0.0"
  return s;
}

// A power of ten as 1, 10, 100 or 10 with its exponent raised (10⁻⁴).
std::string power_label(double v) {
  const int k = static_cast<int>(std::lround(std::log10(v)));
  if (k >= 0 && k <= 2) return fmt::format("{:g}", v);
  static const char* const digits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string s = k < 0 ? "10⁻" : "10";
  for (const char c : std::to_string(std::abs(k))) s += digits[c - '0'];
  return s;
}

}  // namespace

Chart::Chart(std::string title, std::string x_title, std::string y_title, double width, double height)
    : title_(std::move(title)), x_title_(std::move(x_title)), y_title_(std::move(y_title)), width_(width), height_(height) {}

void Chart::extend(double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  if (!any_data_) {
    dx_lo_ = dx_hi_ = x;
    dy_lo_ = dy_hi_ = y;
    any_data_ = true;
    return;
  }
  dx_lo_ = std::min(dx_lo_, x), dx_hi_ = std::max(dx_hi_, x);
  dy_lo_ = std::min(dy_lo_, y), dy_hi_ = std::max(dy_hi_, y);
}

void Chart::add_legend(const std::string& label, const std::string& colour, const char* kind) {
  if (!label.empty()) legend_.push_back({label, colour, kind});
}

void Chart::bars(const std::vector<double>& edges, const std::vector<double>& heights, const std::string& colour,
                 const std::string& label) {
  Item it{Item::Kind::Bars, edges, heights, {}, colour, colour, {}};
  for (std::size_t i = 0; i < heights.size() && i + 1 < edges.size(); ++i) extend(edges[i], 0), extend(edges[i + 1], heights[i]);
  items_.push_back(std::move(it));
  add_legend(label, colour, "box");
}

void Chart::line(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour, const std::string& label,
                 bool markers, bool dashed) {
  Item it{Item::Kind::Line, x, y, {}, colour, {}, {}};
  it.markers = markers, it.dashed = dashed;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) extend(x[i], y[i]);
  items_.push_back(std::move(it));
  add_legend(label, colour, dashed ? "dash" : "line");
}

void Chart::polyline(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour, const std::string& label,
                     double width, double opacity) {
  line(x, y, colour, label, false);
  items_.back().width = width;
  items_.back().opacity = opacity;
}

void Chart::band(const std::vector<double>& x, const std::vector<double>& lo, const std::vector<double>& hi, const std::string& colour,
                 const std::string& label) {
  Item it{Item::Kind::Band, x, lo, hi, colour, colour, {}};
  it.opacity = 0.2;
  for (std::size_t i = 0; i < x.size(); ++i) extend(x[i], lo[i]), extend(x[i], hi[i]);
  items_.push_back(std::move(it));
  add_legend(label, colour, "box");
}

void Chart::error_bars(const std::vector<double>& x, const std::vector<double>& lo, const std::vector<double>& hi,
                       const std::string& colour) {
  Item it{Item::Kind::ErrorBars, x, lo, hi, colour, {}, {}};
  for (std::size_t i = 0; i < x.size(); ++i) extend(x[i], lo[i]), extend(x[i], hi[i]);
  items_.push_back(std::move(it));
}

void Chart::points(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour, const std::string& label,
                   double radius, bool filled) {
  Item it{Item::Kind::Points, x, y, {}, colour, {}, {}};
  it.radius = radius, it.filled = filled;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) extend(x[i], y[i]);
  items_.push_back(std::move(it));
  add_legend(label, colour, "dot");
}

void Chart::segments(const std::vector<double>& x0, const std::vector<double>& y0, const std::vector<double>& x1,
                     const std::vector<double>& y1, const std::string& colour, const std::string& label, double width) {
  // Stored as x = x0 followed by x1, y = y0, y2 = y1.
  Item it{Item::Kind::Segments, x0, y0, y1, colour, {}, {}};
  it.x.insert(it.x.end(), x1.begin(), x1.end());
  it.radius = width;
  for (std::size_t i = 0; i < x0.size(); ++i) extend(x0[i], y0[i]), extend(x1[i], y1[i]);
  items_.push_back(std::move(it));
  add_legend(label, colour, "line");
}

void Chart::triangles(const std::vector<double>& x, const std::vector<double>& y, const std::string& fill, double opacity,
                      const std::string& label) {
  Item it{Item::Kind::Triangles, x, y, {}, fill, fill, {}};
  it.opacity = opacity;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) extend(x[i], y[i]);
  items_.push_back(std::move(it));
  add_legend(label, fill, "box");
}

void Chart::rect(double x0, double y0, double x1, double y1, const std::string& fill, double opacity, const std::string& label) {
  Item it{Item::Kind::Rect, {x0, x1}, {y0, y1}, {}, fill, fill, {}};
  it.opacity = opacity;
  extend(x0, y0), extend(x1, y1);
  items_.push_back(std::move(it));
  add_legend(label, fill, "box");
}

void Chart::vline(double x, const std::string& colour, const std::string& label, bool dashed) {
  Item it{Item::Kind::VLine, {x}, {}, {}, colour, {}, label};
  it.dashed = dashed;
  if (std::isfinite(x)) extend(x, any_data_ ? dy_lo_ : 0);
  items_.push_back(std::move(it));
}

void Chart::hline(double y, const std::string& colour, const std::string& label, bool dashed) {
  Item it{Item::Kind::HLine, {}, {y}, {}, colour, {}, label};
  it.dashed = dashed;
  if (std::isfinite(y)) extend(any_data_ ? dx_lo_ : 0, y);
  items_.push_back(std::move(it));
}

void Chart::circle(double cx, double cy, double r, const std::string& stroke, const std::string& label, bool dashed) {
  Item it{Item::Kind::Circle, {cx}, {cy}, {}, stroke, {}, {}};
  it.radius = r, it.dashed = dashed;
  extend(cx - r, cy - r), extend(cx + r, cy + r);
  items_.push_back(std::move(it));
  add_legend(label, stroke, dashed ? "dash" : "line");
}

// The plot area in pixels and the data ranges it shows, with their ticks.
struct Chart::Frame {
  double xlo = 0, xhi = 1, ylo = 0, yhi = 1, plot_w = 0, plot_h = 0;
  std::vector<double> xt, yt;
  double sx(double x) const { return kLeft + (x - xlo) / (xhi - xlo) * plot_w; }
  bool ylog = false;
  double sy(double y) const {
    if (ylog) return kTop + std::log10(yhi / std::clamp(y, ylo, yhi)) / std::log10(yhi / ylo) * plot_h;
    return kTop + (yhi - y) / (yhi - ylo) * plot_h;
  }
};

Chart::Frame Chart::frame() const {
  // Axis ranges: fixed, or the data's, widened to the nice ticks around it.
  double xlo = x_fixed_ ? x_lo_ : (any_data_ ? dx_lo_ : 0), xhi = x_fixed_ ? x_hi_ : (any_data_ ? dx_hi_ : 1);
  double ylo = y_fixed_ ? y_lo_ : (any_data_ ? dy_lo_ : 0), yhi = y_fixed_ ? y_hi_ : (any_data_ ? dy_hi_ : 1);
  if (!(xhi > xlo)) xhi = xlo + (xlo != 0 ? std::abs(xlo) * 0.1 : 1.0), xlo -= (xhi - xlo);
  if (!(yhi > ylo)) yhi = ylo + (ylo != 0 ? std::abs(ylo) * 0.1 : 1.0), ylo -= y_fixed_ ? 0 : (yhi - ylo);
  const double plot_w = width_ - kLeft - kRight, plot_h = height_ - kTop - kBottom;
  if (equal_) {  // maps: a margin round the drawing
    const double pad = 0.04 * std::max(xhi - xlo, yhi - ylo);
    xlo -= pad, xhi += pad, ylo -= pad, yhi += pad;
  }
  if (equal_) {  // stretch the shorter axis so one unit is as long on both
    const double per_px = std::max((xhi - xlo) / plot_w, (yhi - ylo) / plot_h);
    const double cx = 0.5 * (xlo + xhi), cy = 0.5 * (ylo + yhi);
    xlo = cx - 0.5 * per_px * plot_w, xhi = cx + 0.5 * per_px * plot_w;
    ylo = cy - 0.5 * per_px * plot_h, yhi = cy + 0.5 * per_px * plot_h;
  }
  std::vector<double> xt = x_ticks_.empty() ? nice_ticks(xlo, xhi) : x_ticks_;
  if (y_log_ && !(ylo > 0 && yhi > ylo)) throw std::invalid_argument("a logarithmic axis needs 0 < low < high");
  std::vector<double> yt;
  if (y_log_)
    for (double k = std::ceil(std::log10(ylo) - 1e-9); k <= std::log10(yhi) + 1e-9; ++k) yt.push_back(std::pow(10.0, k));
  else
    yt = nice_ticks(ylo, yhi);
  if (!x_fixed_ && !equal_ && x_ticks_.empty()) xlo = std::min(xlo, xt.front()), xhi = std::max(xhi, xt.back());
  if (!y_fixed_ && !equal_) ylo = std::min(ylo, yt.front()), yhi = std::max(yhi, yt.back());
  std::erase_if(xt, [&](double t) { return t < xlo - 1e-9 * (xhi - xlo) || t > xhi + 1e-9 * (xhi - xlo); });
  std::erase_if(yt, [&](double t) { return t < ylo - 1e-9 * (yhi - ylo) || t > yhi + 1e-9 * (yhi - ylo); });

  return Frame{xlo, xhi, ylo, yhi, plot_w, plot_h, std::move(xt), std::move(yt), y_log_};
}

namespace {
// Words wrapped into lines of at most `per_line` characters.
std::vector<std::string> wrap_words(const std::string& text, std::size_t per_line) {
  std::vector<std::string> lines;
  std::string line;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() > per_line) lines.push_back(line), line.clear();
    line += (line.empty() ? "" : " ") + word;
    start = end + 1;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}
}  // namespace

void Chart::draw_axes(std::string& o, const Frame& f) const {
  const auto& xt = f.xt;
  const auto& yt = f.yt;
  const double xlo = f.xlo, xhi = f.xhi, ylo = f.ylo, yhi = f.yhi, plot_w = f.plot_w, plot_h = f.plot_h;
  const auto sx = [&](double x) { return f.sx(x); };
  const auto sy = [&](double y) { return f.sy(y); };
  // Grid and ticks.
  const double x_step = xt.size() > 1 ? xt[1] - xt[0] : (xhi - xlo);
  const double y_step = yt.size() > 1 ? yt[1] - yt[0] : (yhi - ylo);
  for (double t : xt)
    fmt::format_to(std::back_inserter(o),
                   "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>"
                   "<text x=\"{0:.1f}\" y=\"{3:.1f}\" text-anchor=\"middle\">{4}</text>\n",
                   sx(t), kTop, kTop + plot_h, kTop + plot_h + 16, tick_label(t, x_step));
  for (double t : yt)
    fmt::format_to(std::back_inserter(o),
                   "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
                   "<text x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
                   kLeft, sy(t), kLeft + plot_w, kLeft - 6, sy(t) + 4, f.ylog ? power_label(t) : tick_label(t, y_step));
  fmt::format_to(std::back_inserter(o),
                 "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" stroke=\"#444\"/>\n", kLeft, kTop,
                 plot_w, plot_h);
  fmt::format_to(std::back_inserter(o), "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", kLeft + plot_w / 2,
                 kTop + plot_h + 36, escape(x_title_));
  fmt::format_to(std::back_inserter(o), "<text transform=\"translate(16 {:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                 kTop + plot_h / 2, escape(y_title_));
}

void Chart::draw_item(std::string& o, const Item& it, const Frame& f, int& vlines) const {
  const double plot_w = f.plot_w, plot_h = f.plot_h;
  const double clip_y = std::clamp(0.0, f.ylo, f.yhi);
  const auto sx = [&](double x) { return f.sx(x); };
  const auto sy = [&](double y) { return f.sy(y); };
  const char* dash = it.dashed ? " stroke-dasharray=\"6 4\"" : "";
  switch (it.kind) {
    case Item::Kind::Segments: {
      const std::size_t n = it.y.size();
      std::string d;
      for (std::size_t i = 0; i < n; ++i)
        fmt::format_to(std::back_inserter(d), "M{:.1f} {:.1f}L{:.1f} {:.1f}", sx(it.x[i]), sy(it.y[i]), sx(it.x[n + i]), sy(it.y2[i]));
      fmt::format_to(std::back_inserter(o),
                     "<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{:.1f}\" stroke-linecap=\"round\"/>\n", d, it.colour,
                     it.radius);
      break;
    }
    case Item::Kind::Triangles: {
      std::string d;
      for (std::size_t i = 0; i + 2 < std::min(it.x.size(), it.y.size()); i += 3)
        fmt::format_to(std::back_inserter(d), "M{:.1f} {:.1f}L{:.1f} {:.1f}L{:.1f} {:.1f}Z", sx(it.x[i]), sy(it.y[i]), sx(it.x[i + 1]),
                       sy(it.y[i + 1]), sx(it.x[i + 2]), sy(it.y[i + 2]));
      fmt::format_to(std::back_inserter(o), "<path d=\"{}\" fill=\"{}\" fill-opacity=\"{:.2f}\" stroke=\"none\"/>\n", d, it.fill,
                     it.opacity);
      break;
    }
    case Item::Kind::Bars: {
      std::string d;
      for (std::size_t i = 0; i < it.y.size() && i + 1 < it.x.size(); ++i) {
        if (it.y[i] <= 0) continue;
        fmt::format_to(std::back_inserter(d), "M{:.1f} {:.1f}H{:.1f}V{:.1f}H{:.1f}Z", sx(it.x[i]), sy(clip_y), sx(it.x[i + 1]), sy(it.y[i]),
                       sx(it.x[i]));
      }
      fmt::format_to(std::back_inserter(o), "<path d=\"{}\" fill=\"{}\" fill-opacity=\"0.75\" stroke=\"{}\" stroke-width=\"0.5\"/>\n", d,
                     it.fill, it.colour);
      break;
    }
    case Item::Kind::Line: {
      std::string d;
      for (std::size_t i = 0; i < std::min(it.x.size(), it.y.size()); ++i)
        if (std::isfinite(it.y[i]))
          fmt::format_to(std::back_inserter(d), "{}{:.1f} {:.1f}", d.empty() ? "M" : "L", sx(it.x[i]), sy(it.y[i]));
      const std::string faint = it.opacity < 1 ? fmt::format(" stroke-opacity=\"{:.2f}\"", it.opacity) : std::string();
      fmt::format_to(std::back_inserter(o), "<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{:.1f}\"{}{}/>\n", d, it.colour,
                     it.width, dash, faint);
      if (it.markers)
        for (std::size_t i = 0; i < std::min(it.x.size(), it.y.size()); ++i)
          if (std::isfinite(it.y[i]))
            fmt::format_to(std::back_inserter(o), "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.8\" fill=\"{}\"/>", sx(it.x[i]), sy(it.y[i]),
                           it.colour);
      o += "\n";
      break;
    }
    case Item::Kind::Band: {
      std::string d;
      for (std::size_t i = 0; i < it.x.size(); ++i)
        fmt::format_to(std::back_inserter(d), "{}{:.1f} {:.1f}", i ? "L" : "M", sx(it.x[i]), sy(it.y2[i]));
      for (std::size_t i = it.x.size(); i-- > 0;) fmt::format_to(std::back_inserter(d), "L{:.1f} {:.1f}", sx(it.x[i]), sy(it.y[i]));
      fmt::format_to(std::back_inserter(o), "<path d=\"{}Z\" fill=\"{}\" fill-opacity=\"{:.2f}\" stroke=\"none\"/>\n", d, it.fill,
                     it.opacity);
      break;
    }
    case Item::Kind::ErrorBars:
      for (std::size_t i = 0; i < it.x.size(); ++i)
        fmt::format_to(
            std::back_inserter(o),
            "<path d=\"M{0:.1f} {1:.1f}V{2:.1f}M{3:.1f} {1:.1f}H{4:.1f}M{3:.1f} {2:.1f}H{4:.1f}\" stroke=\"{5}\" stroke-width=\"1.2\"/>",
            sx(it.x[i]), sy(it.y[i]), sy(it.y2[i]), sx(it.x[i]) - 4, sx(it.x[i]) + 4, it.colour);
      o += "\n";
      break;
    case Item::Kind::Points: {
      if (it.filled) {  // round-capped zero-length strokes: a dot each, compactly
        std::string d;
        for (std::size_t i = 0; i < std::min(it.x.size(), it.y.size()); ++i)
          fmt::format_to(std::back_inserter(d), "M{:.1f} {:.1f}h0", sx(it.x[i]), sy(it.y[i]));
        fmt::format_to(std::back_inserter(o),
                       "<path d=\"{}\" stroke=\"{}\" stroke-width=\"{:.1f}\" stroke-linecap=\"round\" stroke-opacity=\"0.85\"/>\n", d,
                       it.colour, 2 * it.radius);
      } else {
        for (std::size_t i = 0; i < std::min(it.x.size(), it.y.size()); ++i)
          fmt::format_to(std::back_inserter(o), "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{:.1f}\" fill=\"none\" stroke=\"{}\"/>",
                         sx(it.x[i]), sy(it.y[i]), it.radius, it.colour);
        o += "\n";
      }
      break;
    }
    case Item::Kind::Rect: {
      const double x0 = std::min(sx(it.x[0]), sx(it.x[1])), x1 = std::max(sx(it.x[0]), sx(it.x[1]));
      const double y0 = std::min(sy(it.y[0]), sy(it.y[1])), y1 = std::max(sy(it.y[0]), sy(it.y[1]));
      fmt::format_to(std::back_inserter(o),
                     "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\" fill-opacity=\"{:.2f}\"/>\n", x0, y0,
                     x1 - x0, y1 - y0, it.fill, it.opacity);
      break;
    }
    case Item::Kind::VLine:
      fmt::format_to(std::back_inserter(o),
                     "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"{3}\" stroke-width=\"1.5\"{4}/>",
                     sx(it.x[0]), kTop, kTop + plot_h, it.colour, dash);
      if (!it.text.empty())
        fmt::format_to(std::back_inserter(o), "<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"{}\" font-size=\"11\">{}</text>", sx(it.x[0]) + 3,
                       kTop + 12 + 13 * (vlines++ % 4), it.colour, escape(it.text));
      o += "\n";
      break;
    case Item::Kind::HLine:
      fmt::format_to(std::back_inserter(o),
                     "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"{3}\" stroke-width=\"1.5\"{4}/>", kLeft,
                     sy(it.y[0]), kLeft + plot_w, it.colour, dash);
      if (!it.text.empty())
        fmt::format_to(std::back_inserter(o), "<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"{}\" font-size=\"11\">{}</text>", kLeft + 4,
                       sy(it.y[0]) - 3, it.colour, escape(it.text));
      o += "\n";
      break;
    case Item::Kind::Circle:
      fmt::format_to(
          std::back_inserter(o),
          "<ellipse cx=\"{:.1f}\" cy=\"{:.1f}\" rx=\"{:.1f}\" ry=\"{:.1f}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"{}/>\n",
          sx(it.x[0]), sy(it.y[0]), std::abs(sx(it.x[0] + it.radius) - sx(it.x[0])), std::abs(sy(it.y[0] + it.radius) - sy(it.y[0])),
          it.colour, dash);
      break;
  }
}

void Chart::draw_legend(std::string& o, int legend_cols, const std::vector<std::string>& caption_lines) const {
  const int legend_rows = static_cast<int>((legend_.size() + legend_cols - 1) / legend_cols);
  // Legend below the axes.
  for (std::size_t i = 0; i < legend_.size(); ++i) {
    const double x = kLeft + static_cast<double>(i % legend_cols) * 200;
    const double y = height_ + static_cast<double>(i / legend_cols) * kLegendRow + 2;
    const auto& e = legend_[i];
    if (e.kind == "box")
      fmt::format_to(std::back_inserter(o), "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"16\" height=\"10\" fill=\"{}\" fill-opacity=\"0.6\"/>",
                     x, y - 9, e.colour);
    else if (e.kind == "dot")
      fmt::format_to(std::back_inserter(o), "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"/>", x + 8, y - 4, e.colour);
    else
      fmt::format_to(std::back_inserter(o),
                     "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" stroke-width=\"2\"{}/>", x, y - 4, x + 16,
                     y - 4, e.colour, e.kind == "dash" ? " stroke-dasharray=\"5 3\"" : "");
    fmt::format_to(std::back_inserter(o), "<text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", x + 21, y, escape(e.label));
  }
  for (std::size_t i = 0; i < caption_lines.size(); ++i)
    fmt::format_to(std::back_inserter(o), "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"#444\">{}</text>\n", kLeft,
                   height_ + legend_rows * kLegendRow + 8 + 14 * static_cast<double>(i), escape(caption_lines[i]));
}

std::string Chart::svg() const {
  const Frame f = frame();
  const double plot_w = f.plot_w, plot_h = f.plot_h;
  const int legend_cols = std::max(1, static_cast<int>((width_ - kLeft) / 200));
  const int legend_rows = static_cast<int>((legend_.size() + legend_cols - 1) / legend_cols);
  // The caption, wrapped at about 6 px a character.
  const std::vector<std::string> caption_lines = wrap_words(caption_, static_cast<std::size_t>(std::max(20.0, (width_ - kLeft) / 6.0)));
  const double total_h =
      height_ + legend_rows * kLegendRow + static_cast<double>(caption_lines.size()) * 14 + (caption_lines.empty() ? 0 : 6);

  std::string o;
  o.reserve(8192);
  // Clip-path ids must be unique within a document: derive one from the title.
  std::string clip = "clip-";
  for (char c : title_) clip += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  fmt::format_to(std::back_inserter(o),
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart\" viewBox=\"0 0 {:.0f} {:.0f}\" width=\"{:.0f}\" "
                 "height=\"{:.0f}\" font-family=\"sans-serif\" font-size=\"12\" role=\"img\" aria-label=\"{}\">\n",
                 width_, total_h, width_, total_h, escape(title_));
  fmt::format_to(std::back_inserter(o), "<title>{}</title>\n", escape(title_));
  fmt::format_to(std::back_inserter(o),
                 "<defs><clipPath id=\"{}\"><rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\"/></clipPath></defs>\n", clip,
                 kLeft, kTop, plot_w, plot_h);
  // A long title is set smaller rather than cut off (about 0.58 em a character).
  const double title_size =
      std::clamp((width_ - kLeft - 4) / (0.58 * static_cast<double>(std::max<std::size_t>(1, title_.size()))), 9.0, 14.0);
  fmt::format_to(std::back_inserter(o), "<text x=\"{:.1f}\" y=\"20\" font-size=\"{:.1f}\" font-weight=\"bold\">{}</text>\n", kLeft,
                 title_size, escape(title_));
  draw_axes(o, f);
  // Data, clipped to the plot area.
  fmt::format_to(std::back_inserter(o), "<g clip-path=\"url(#{})\">\n", clip);
  int vlines = 0;  // labels of successive vertical lines step down, so they do not overlap
  for (const Item& it : items_) draw_item(o, it, f, vlines);
  o += "</g>\n";
  draw_legend(o, legend_cols, caption_lines);
  o += "</svg>\n";
  return o;
}

}  // namespace j232::report
