# Writes OUTPUT (a C++ source defining j232::git_revision) from the source tree's git
# revision, run at every build (not only at configure time, so that a result's provenance
# names the code that wrote it) and rewriting the file only when the revision changed (so
# an unchanged tree rebuilds nothing). "-dirty": the tree differs from that commit.
execute_process(COMMAND git rev-parse --short HEAD WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE failed)
if(failed OR NOT revision)
  set(revision unknown)
else()
  execute_process(COMMAND git diff --quiet HEAD -- WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE changed ERROR_QUIET)
  if(changed)
    set(revision "${revision}-dirty")
  endif()
endif()
set(text "// Generated at build time by cmake/git_revision.cmake: the source revision this build was\n// made from (every result's provenance names it).\n#include \"j232/version.hpp\"\n\nnamespace j232 {\nconst char* const git_revision = \"${revision}\";\n}  // namespace j232\n")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUTPUT} "${text}")
endif()
