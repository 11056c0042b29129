# A campaign run once for the tests that read it (a ctest fixture, issue 28): `crankcheck ARGS... --out DIR/report`,
# its stdout, stderr and exit status kept beside the report in DIR (stdout.txt, stderr.txt, status.txt) for the
# readers' own checks. The folder is the fixture's, in the build tree, made fresh here each time. Run by ctest as
#   cmake -DCRANKCHECK=... -DDIR=... "-DARGS=validate --quick" -P campaign_fixture.cmake
# (ARGS split as a shell would, without one: separate_arguments UNIX_COMMAND).
# Fails (and ctest then runs none of its readers) when crankcheck does not exit with status 0.
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${DIR})
file(MAKE_DIRECTORY ${DIR})
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND ${CRANKCHECK} ${args} --out ${DIR}/report RESULT_VARIABLE status
                OUTPUT_FILE ${DIR}/stdout.txt ERROR_FILE ${DIR}/stderr.txt
                TIMEOUT 600)  # never waited on without a limit (a full campaign takes about 30 s)
file(WRITE ${DIR}/status.txt "${status}\n")
if(NOT status EQUAL 0)
  file(READ ${DIR}/stdout.txt out)
  file(READ ${DIR}/stderr.txt err)
  message(FATAL_ERROR "crankcheck ${ARGS} --out ${DIR}/report: exit status ${status}\n${out}\n${err}")
endif()
message(STATUS "crankcheck ${ARGS} --out ${DIR}/report: status 0")
