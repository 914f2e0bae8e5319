#pragma once
// Cheap invariant checks where the code assumes something (in the manner of pbrt's CHECK):
// on unless the build says otherwise (CMake option J232_CHECKS, on by default, so the tests,
// the checked build and the program all run them; each costs a comparison). A failed check
// names the file, line and condition and aborts: an assumption that does not hold is a bug
// to find, never a state to run on from.
#include <cstdio>
#include <cstdlib>

#if defined(J232_CHECKS)
#define J232_CHECK(condition)                                                                               \
  do {                                                                                                      \
    if (!(condition)) {                                                                                     \
      std::fprintf(stderr, "%s:%d: invariant failed: %s\n", __FILE__, __LINE__, #condition);               \
      std::abort();                                                                                         \
    }                                                                                                       \
  } while (false)
#else
#define J232_CHECK(condition) \
  do {                        \
    (void)sizeof(condition);  \
  } while (false)
#endif
