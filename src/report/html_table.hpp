#pragma once
// A table of an HTML page, built a row at a time: a header row, rows of cells, each cell's
// HTML given as it is to be written (text escaped by the caller, report::escape). One place
// writes the markup, so a page's tables cannot drift apart in it:
//   <table><tr><th>a</th><th>b</th></tr>\n<tr><td>1</td><td>2</td></tr>\n</table>\n
#include <string>
#include <vector>

namespace j232::report {

class HtmlTable {
 public:
  explicit HtmlTable(const std::vector<std::string>& header) {
    out_ = "<table>";
    add("th", header);
  }
  HtmlTable& row(const std::vector<std::string>& cells) {
    add("td", cells);
    return *this;
  }
  std::string html() const { return out_ + "</table>\n"; }

 private:
  void add(const char* tag, const std::vector<std::string>& cells) {
    out_ += "<tr>";
    for (const auto& c : cells) out_ += std::string("<") + tag + ">" + c + "</" + tag + ">";
    out_ += "</tr>\n";
  }
  std::string out_;
};

}  // namespace j232::report
