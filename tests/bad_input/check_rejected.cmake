# Runs tissuefem on an input that must fail, in an empty directory, and
# checks that it fails cleanly: exit status EXPECTED_STATUS (2: bad input,
# 3: solver failure), one line on stderr naming the culprit (EXPECTED, and
# not UNEXPECTED where given), and no files written; or, with ALLOW_FILES (a
# run that starts and then fails in the solver), no "nan" in any file
# written. With PROCESSES, it runs on that many MPI processes.
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
set(launcher "")
if(PROCESSES)
  set(launcher mpirun -np ${PROCESSES})
endif()
execute_process(COMMAND ${launcher} ${TISSUEFEM} ${INPUT}
  WORKING_DIRECTORY ${WORKDIR}
  RESULT_VARIABLE status
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
if(NOT status EQUAL EXPECTED_STATUS)
  message(FATAL_ERROR "exit status ${status}, expected ${EXPECTED_STATUS}: ${err}")
endif()
if(PROCESSES)
  # mpirun reports the failed process after tissuefem's line, beginning
  # with a line of dashes.
  string(REGEX REPLACE "-----.*" "" err "${err}")
endif()
string(STRIP "${err}" err)
string(FIND "${err}" "\n" newline)
if(NOT newline EQUAL -1)
  message(FATAL_ERROR "error message is not one line:\n${err}")
endif()
string(FIND "${err}" "${EXPECTED}" found)
if(found EQUAL -1)
  message(FATAL_ERROR "error message '${err}' does not name '${EXPECTED}'")
endif()
if(UNEXPECTED)
  string(FIND "${err}" "${UNEXPECTED}" found)
  if(NOT found EQUAL -1)
    message(FATAL_ERROR "error message '${err}' names '${UNEXPECTED}'")
  endif()
endif()
if(ALLOW_FILES)
  # CSV files are plain text; VTU data are compressed, and the writer refuses
  # to write non-finite fields (it stops with a solver error instead).
  file(GLOB_RECURSE written ${WORKDIR}/*.csv)
  foreach(f ${written})
    file(STRINGS ${f} nan_lines REGEX "[Nn][Aa][Nn]")
    if(nan_lines)
      message(FATAL_ERROR "${f} contains NaN: ${nan_lines}")
    endif()
  endforeach()
else()
  file(GLOB written ${WORKDIR}/*)
  if(written)
    message(FATAL_ERROR "files were written despite the error: ${written}")
  endif()
endif()
message(STATUS "rejected with: ${err}")
