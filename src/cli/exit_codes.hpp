#pragma once
// Exit codes of the j232 program (documented in README.md).
namespace j232::cli {
inline constexpr int kOk = 0;           // ran; for `run`: the simulated mower passes
inline constexpr int kFails = 1;        // ran; the simulated mower fails the criteria
inline constexpr int kBadInput = 2;     // refused the input (file, key, value and what was expected on stderr)
inline constexpr int kInternal = 3;     // a bug: please report it with the input that caused it
}  // namespace j232::cli
