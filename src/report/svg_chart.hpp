#pragma once
// A small chart maker for reports: inline SVG with axes, "nice" ticks, gridlines,
// units in the axis titles and a legend. Everything a report draws (histograms,
// sweep curves, interval charts, the hit map) goes through it, so every chart has
// the same look and every axis names its quantity and unit.
#include <string>
#include <vector>

namespace j232::report {

// Colour-blind-safe palette (Okabe & Ito, 2008), cycled for series.
const std::string& palette(std::size_t i);

// About `target` round-numbered ticks covering [lo, hi] (steps of 1, 2 or 5 x 10^k).
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

// Escapes &, <, >, " for HTML and SVG text.
std::string escape(const std::string& text);

class Chart {
 public:
  Chart(std::string title, std::string x_title, std::string y_title, double width = 640, double height = 360);

  // Axis ranges; unset ranges are fitted to the data drawn, widened to nice ticks.
  void x_range(double lo, double hi) { x_lo_ = lo, x_hi_ = hi, x_fixed_ = true; }
  void y_range(double lo, double hi) { y_lo_ = lo, y_hi_ = hi, y_fixed_ = true; }
  // A logarithmic y axis from lo to hi (both above zero; ticks at the powers of ten between):
  // values at or below lo, zero among them, are drawn on the axis's floor.
  void y_log_range(double lo, double hi) { y_range(lo, hi), y_log_ = true; }
  // Custom tick labels (for example azimuths); positions in data units.
  void x_ticks(std::vector<double> at) { x_ticks_ = std::move(at); }
  void equal_aspect() { equal_ = true; }  // one data unit is as long on both axes (plan views)

  // Series. `label` empty: no legend entry.
  void bars(const std::vector<double>& edges, const std::vector<double>& heights, const std::string& colour, const std::string& label);
  void line(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour, const std::string& label,
            bool markers = true, bool dashed = false);
  // A thin, see-through line without markers: many paths over one another.
  void polyline(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour, const std::string& label,
                double width, double opacity);
  void band(const std::vector<double>& x, const std::vector<double>& lo, const std::vector<double>& hi, const std::string& colour,
            const std::string& label);
  void error_bars(const std::vector<double>& x, const std::vector<double>& lo, const std::vector<double>& hi, const std::string& colour);
  void points(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour, const std::string& label,
              double radius = 2.5, bool filled = true);
  // Many straight segments (x0[i],y0[i])-(x1[i],y1[i]) as one path; many triangles as one
  // filled path (painted once, so overlaps do not darken).
  void segments(const std::vector<double>& x0, const std::vector<double>& y0, const std::vector<double>& x1, const std::vector<double>& y1,
                const std::string& colour, const std::string& label, double width = 1.2);
  void triangles(const std::vector<double>& x, const std::vector<double>& y, const std::string& fill, double opacity,
                 const std::string& label);  // vertices 3 by 3
  void rect(double x0, double y0, double x1, double y1, const std::string& fill, double opacity, const std::string& label);
  void vline(double x, const std::string& colour, const std::string& label, bool dashed = true);
  void hline(double y, const std::string& colour, const std::string& label, bool dashed = true);
  void circle(double cx, double cy, double r, const std::string& stroke, const std::string& label, bool dashed = false);
  void caption(std::string text) { caption_ = std::move(text); }

  std::string svg() const;

 private:
  // One drawn thing, kept in data units until the axes are known.
  struct Item {
    enum class Kind { Segments, Triangles, Bars, Line, Band, ErrorBars, Points, Rect, VLine, HLine, Circle } kind;
    std::vector<double> x, y, y2;
    std::string colour, fill, text;
    bool markers = false, dashed = false, filled = true;
    double radius = 0, opacity = 1, width = 1.8;
  };
  std::vector<Item> items_;
  struct LegendEntry {
    std::string label, colour, kind;
  };
  std::vector<LegendEntry> legend_;
  void extend(double x, double y);
  void add_legend(const std::string& label, const std::string& colour, const char* kind);

  // Drawing (svg()): the axes' ranges and ticks, then each part in turn.
  struct Frame;
  Frame frame() const;
  void draw_axes(std::string& o, const Frame& f) const;
  void draw_item(std::string& o, const Item& it, const Frame& f, int& vlines) const;
  void draw_legend(std::string& o, int columns, const std::vector<std::string>& caption_lines) const;

  std::string title_, x_title_, y_title_, caption_;
  double width_, height_;
  double x_lo_ = 0, x_hi_ = 0, y_lo_ = 0, y_hi_ = 0;
  bool x_fixed_ = false, y_fixed_ = false, equal_ = false, any_data_ = false, y_log_ = false;
  double dx_lo_ = 0, dx_hi_ = 0, dy_lo_ = 0, dy_hi_ = 0;
  std::vector<double> x_ticks_;
};

}  // namespace j232::report
