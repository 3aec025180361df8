# Runs a unit test with TISSUEFEM_TESTS_FEED_NAN set (its first reduced
# value becomes NaN, tests.h) and passes only if the test then fails: a
# non-zero exit status and at least one "FAILED" line.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} --target ${TARGET}
                RESULT_VARIABLE built OUTPUT_QUIET)
if(NOT built EQUAL 0)
  message(FATAL_ERROR "could not build ${TARGET}")
endif()
file(MAKE_DIRECTORY ${WORKDIR})
set(ENV{TISSUEFEM_TESTS_FEED_NAN} 1)
execute_process(COMMAND ${EXECUTABLE}
                WORKING_DIRECTORY ${WORKDIR}
                RESULT_VARIABLE status
                OUTPUT_VARIABLE output
                ERROR_VARIABLE errors)
if(status EQUAL 0)
  message(FATAL_ERROR "${TARGET} passed with a NaN fed to its checks:\n${output}")
endif()
if(NOT output MATCHES "FAILED")
  message(FATAL_ERROR "${TARGET} exited with ${status} but printed no FAILED "
                      "check with a NaN fed to it:\n${output}\n${errors}")
endif()
message(STATUS "${TARGET} fails as it must with a NaN fed to it")
