#pragma once
// Exit codes of the j232 program (documented in README.md).
namespace j232::cli {
inline constexpr int kOk = 0;        // ran; for `run`: the simulated mower passes
inline constexpr int kFails = 1;     // ran; the simulated mower fails the criteria
inline constexpr int kBadInput = 2;  // refused: bad input (file, key, value, what was expected), or an output
                                     // folder that cannot be written (path and the system's reason)
inline constexpr int kInternal = 3;  // a bug: please report it with the input that caused it
inline constexpr int kInvalid = 4;   // ran, but the simulated test did not really happen: no verdict (reasons printed)
}  // namespace j232::cli
