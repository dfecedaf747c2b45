# Writes OUT (a header defining EVMS_VERSION from `git describe`) when its text changes, so that
# each build names the commit it was built from without rebuilding what includes it needlessly.
execute_process(COMMAND git describe --always --dirty --tags WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE describe OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR describe STREQUAL "")
  set(describe "unknown (not built from a git clone)")
endif()
set(text "#pragma once\n#define EVMS_VERSION \"${describe}\"\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
