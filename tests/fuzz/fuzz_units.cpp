// libFuzzer target: the unit parser. Any text either parses to a finite SI value or is
// refused with a UnitError; nothing else may happen (no crash, no overflow, no NaN).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "units/quantity.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  using j232::units::Kind;
  const auto kind = static_cast<Kind>(data[0] % (static_cast<int>(Kind::PerArea) + 1));
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const double v = j232::units::parse(text, kind);
    if (!std::isfinite(v)) std::abort();
  } catch (const j232::units::UnitError&) {
  }
  return 0;
}
