#include "report/html_page.hpp"

#include <fmt/format.h>
#include <stdexcept>
#include <string_view>

#include "report/svg_chart.hpp"
#include "report/result_files.hpp"

namespace j232::report {

namespace {
constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", "Helvetica Neue", Arial, sans-serif; color: #222; max-width: 960px; margin: 24px auto; padding: 0 16px; line-height: 1.4; }
h1 { font-size: 22px; margin-bottom: 2px; }
h2 { font-size: 17px; border-bottom: 1px solid #ccc; padding-bottom: 3px; margin-top: 28px; }
.sub { color: #555; margin-top: 0; }
.caps { text-transform: uppercase; }
.verdict { border-radius: 6px; padding: 10px 16px; margin: 16px 0; }
.verdict.pass { background: #e6f4ea; border: 2px solid #2e7d32; }
.verdict.fail { background: #fdecea; border: 2px solid #c62828; }
.verdict-line { font-size: 18px; font-weight: bold; margin: 4px 0; }
table { border-collapse: collapse; margin: 8px 0; font-size: 13px; }
th, td { border-bottom: 1px solid #e3e3e3; padding: 4px 10px; text-align: left; vertical-align: top; }
th { background: #f3f3f3; }
table.numbers td:not(:first-child) { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
table.keys td:first-child { font-family: monospace; color: #444; }
tr.deciding { background: #fff4d6; }
tr.fails td.verdict-cell { color: #c62828; font-weight: bold; }
tr.passes td.verdict-cell { color: #2e7d32; font-weight: bold; }
tr.error td { color: #c62828; }
.bar { display: inline-block; height: 10px; background: #0072B2; opacity: 0.7; }
figure { margin: 14px 0; break-inside: avoid; page-break-inside: avoid; }
figcaption { font-size: 12px; color: #555; max-width: 860px; }
svg.chart { max-width: 100%; height: auto; }
footer { margin-top: 32px; font-size: 11px; color: #777; }
@page { size: A4; margin: 14mm; }
@media print { body { margin: 0; max-width: none; } h2 { break-after: avoid; } section { break-inside: auto; } }
)";
}  // namespace

std::string page_head(const std::string& title) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n<style>{}</style>\n"
      "</head>\n<body>\n",
      escape(title), kStyle);
}

std::string page_foot() {
  return "<footer>Written by j232, a Monte Carlo simulation of the SAE J232 thrown-object test built on the impact models of "
         "report 445-1. A simulated verdict supports, and does not replace, the physical test.</footer>\n</body>\n</html>\n";
}

long long whole(const nlohmann::ordered_json& value, const char* what, long long lowest, long long highest) {
  if (value.is_number_unsigned() && value.get<std::uint64_t>() <= static_cast<std::uint64_t>(highest) && lowest <= highest) {
    const auto v = static_cast<long long>(value.get<std::uint64_t>());
    if (v >= lowest) return v;
  } else if (value.is_number_integer() && !value.is_number_unsigned()) {
    const auto v = value.get<long long>();
    if (v >= lowest && v <= highest) return v;
  }
  throw std::out_of_range(fmt::format("{}: expected a whole number from {} to {}, not {}", what, lowest, highest, json_text(value, -1)));
}

std::string number(const std::string& key, const nlohmann::ordered_json& value, const char* format, double scale) {
  std::string shown;
  const bool as_integer = value.is_number_integer() && scale == 1.0 && std::string_view(format).find('.') == std::string_view::npos;
  if (as_integer)
    shown = fmt::format(fmt::runtime(format), value.get<long long>());
  else if (value.is_number())
    shown = fmt::format(fmt::runtime(format), value.get<double>() * scale);
  else
    shown = value.is_string() ? value.get<std::string>() : value.dump();
  return fmt::format("<span data-key=\"{}\" data-value=\"{}\" data-scale=\"{:g}\">{}</span>", escape(key), escape(json_text(value, -1)), scale,
                     escape(shown));
}

}  // namespace j232::report
