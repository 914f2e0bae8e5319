#pragma once
// The frame shared by every HTML page j232 writes (compliance report, batch summary):
// one style sheet, inline, that reads well on screen and prints to A4.
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace j232::report {

std::string page_head(const std::string& title);
std::string page_foot();

// A number shown as `format` of value x scale, tagged with the result.json key it came
// from and its exact value, so tests can check the page against the file.
std::string number(const std::string& key, const nlohmann::ordered_json& value, const char* format, double scale = 1.0);

// A whole number a page reads from a saved file: an integer from `lowest` to `highest`, else
// std::out_of_range naming `what` (a real, or one out of range, would be cast unchecked).
long long whole(const nlohmann::ordered_json& value, const char* what, long long lowest, long long highest);
inline std::uint64_t count_of(const nlohmann::ordered_json& value, const char* what) {
  return static_cast<std::uint64_t>(whole(value, what, 0, std::numeric_limits<long long>::max()));
}

}  // namespace j232::report
