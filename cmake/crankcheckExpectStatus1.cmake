# crankcheck_add_free_run_grade_test(... WILL_FAIL): runs the command after `--` (crankcheck and its arguments, each
# with a `+` before it) and succeeds only when it exits with status 1 (a run graded and found out of tolerance);
# 0 (it passed), 2 (bad usage) and 3 (a broken run, a program that could not be run) fail. Its output is passed
# through.
#
#   cmake -P crankcheckExpectStatus1.cmake -- +/path/to/crankcheck +grade +--free-run ...
#
# Each argument reaches crankcheck exactly, its `+` removed: one holding `;` and an empty one (`+`) included. The `+`
# keeps cmake from reading an argument as its own option: cmake 3.25 still reads some after `--` (-P among them), none
# that starts with `+`.
cmake_minimum_required(VERSION 3.25)
include("${CMAKE_CURRENT_LIST_DIR}/crankcheckGrade.cmake")   # _crankcheck_quote
set(command "")   # CMake code: one bracket argument per argument
set(in_command FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE 1 ${last})
  if(in_command)
    if(NOT CMAKE_ARGV${i} MATCHES "^[+]")
      message(FATAL_ERROR "crankcheckExpectStatus1.cmake: argument ${i} does not start with +: ${CMAKE_ARGV${i}}")
    endif()
    string(SUBSTRING "${CMAKE_ARGV${i}}" 1 -1 argument)
    _crankcheck_quote(quoted "${argument}")
    string(APPEND command " ${quoted}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")   # the first: before it only cmake's own options and this file
    set(in_command TRUE)
  endif()
endforeach()
if(command STREQUAL "")
  message(FATAL_ERROR "crankcheckExpectStatus1.cmake: no command after --")
endif()
cmake_language(EVAL CODE "execute_process(COMMAND${command} RESULT_VARIABLE status)")
if(NOT status STREQUAL "1")
  message(FATAL_ERROR "expected exit status 1 (graded, out of tolerance), got ${status}")
endif()
