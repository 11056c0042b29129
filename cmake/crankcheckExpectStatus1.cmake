# crankcheck_add_free_run_grade_test(... WILL_FAIL): runs `CRANKCHECK ARGS...` and succeeds only when it exits with
# status 1 (a run graded and found out of tolerance); 0 (it passed), 2 (bad usage) and 3 (a broken run, a program that
# could not be run) fail. Its output is passed through.
#
#   cmake -DCRANKCHECK=/path/to/crankcheck "-DARGS=grade;--free-run;..." -P crankcheckExpectStatus1.cmake
execute_process(COMMAND ${CRANKCHECK} ${ARGS} RESULT_VARIABLE status)
if(NOT status STREQUAL "1")
  message(FATAL_ERROR "expected exit status 1 (graded, out of tolerance), got ${status}")
endif()
