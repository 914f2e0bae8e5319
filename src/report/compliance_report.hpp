#pragma once
// report.html: what a safety engineer files. One self-contained page (inline CSS and
// SVG, nothing fetched, no scripts) that prints to PDF: verdict, criteria, hit map and
// plan view, speed and energy histograms, where the nails went, the scenario as run,
// assumptions with sources and provenance. Every key number carries
// data-key / data-value attributes naming its place in result.json, so a test can check
// the page against the file.
#include <nlohmann/json.hpp>
#include <string>

namespace j232::report {

// Drawn from a result.json as saved (report::as_saved) alone, "pictures" included: the page
// `j232 run` writes and the one `j232 redraw` draws from the saved file are the same.
std::string compliance_report_html(const nlohmann::ordered_json& result);

}  // namespace j232::report
