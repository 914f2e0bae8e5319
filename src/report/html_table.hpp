#pragma once
// A table of an HTML page, built a row at a time: a header row, rows of cells, each cell's
// HTML given as it is to be written (text escaped by the caller, report::escape). One place
// writes the markup, so a page's tables cannot drift apart in it. Plain:
//   <table><tr><th>a</th><th>b</th></tr>\n<tr><td>1</td><td>2</td></tr>\n</table>\n
// or, with a class (a table of figures, "numbers": right-aligned columns), in sections:
//   <table class="numbers"><thead><tr><th>a</th></tr></thead><tbody>\n<tr><td>1</td></tr>\n</tbody></table>\n
// (an empty class: `<table><thead>`), or a body without a header (`without_header("keys")`,
// a list of keys and values):
//   <table class="keys"><tbody>\n<tr><td>seed</td><td>7</td></tr>\n</tbody></table>\n
// A row may carry attributes of its own (` class="deciding"`).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace j232::report {

// A cell's HTML and, rarely, its attributes (` colspan="6"`, from `spanning`; ` rowspan="2"`,
// from `spanning_rows`; ` class="verdict-cell"`, from `of_class`).
struct HtmlCell {
  std::string html, attributes;
  HtmlCell(std::string h) : html(std::move(h)) {}  // NOLINT: a cell is usually just its HTML
  HtmlCell(const char* h) : html(h) {}             // NOLINT
  // A cell across `columns` columns.
  static HtmlCell spanning(int columns, std::string h) {
    HtmlCell c(std::move(h));
    c.attributes = " colspan=\"" + std::to_string(columns) + "\"";
    return c;
  }
  // A cell down `rows` rows (the rows below leave its column out).
  static HtmlCell spanning_rows(std::size_t rows, std::string h) {
    HtmlCell c(std::move(h));
    c.attributes = " rowspan=\"" + std::to_string(rows) + "\"";
    return c;
  }
  static HtmlCell of_class(const std::string& css_class, std::string h) {
    HtmlCell c(std::move(h));
    c.attributes = " class=\"" + css_class + "\"";
    return c;
  }
};

class HtmlTable {
 public:
  explicit HtmlTable(const std::vector<HtmlCell>& header) {
    out_ = "<table>";
    add("th", header, "");
    out_ += "\n";
  }
  HtmlTable(const std::string& css_class, const std::vector<HtmlCell>& header) : sections_(true) {
    out_ = open_tag(css_class) + "<thead>";
    add("th", header, "");
    out_ += "</thead><tbody>\n";
  }
  static HtmlTable without_header(const std::string& css_class) {
    HtmlTable t;
    t.out_ = open_tag(css_class) + "<tbody>\n";
    t.sections_ = true;
    return t;
  }
  HtmlTable& row(const std::vector<HtmlCell>& cells, const std::string& row_attributes = "") {
    add("td", cells, row_attributes);
    out_ += "\n";
    return *this;
  }
  std::string html() const { return out_ + (sections_ ? "</tbody></table>\n" : "</table>\n"); }

 private:
  HtmlTable() = default;
  static std::string open_tag(const std::string& css_class) {
    return css_class.empty() ? "<table>" : "<table class=\"" + css_class + "\">";
  }
  void add(const char* tag, const std::vector<HtmlCell>& cells, const std::string& row_attributes) {
    out_ += "<tr" + row_attributes + ">";
    for (const auto& c : cells) out_ += std::string("<") + tag + c.attributes + ">" + c.html + "</" + tag + ">";
    out_ += "</tr>";
  }
  std::string out_;
  bool sections_ = false;
};

}  // namespace j232::report
