#pragma once
// report.html: what a safety engineer files. One self-contained page (inline CSS and
// SVG, nothing fetched, no scripts) that prints to PDF: verdict, criteria, hit map and
// plan view, speed and energy histograms, where the nails went, the scenario as run,
// assumptions with sources and provenance. Every key number carries
// data-key / data-value attributes naming its place in result.json, so a test can check
// the page against the file.
#include <nlohmann/json.hpp>
#include <string>

#include "assess/summary.hpp"
#include "scene/soup.hpp"

namespace j232::report {

// `result` is result_json() of the same run; `soup` the scene the run used.
std::string compliance_report_html(const scenario::Scenario& s, const assess::Assessment& a, const assess::Summary& sum,
                                   const nlohmann::ordered_json& result, const scene::Soup& soup);

}  // namespace j232::report
