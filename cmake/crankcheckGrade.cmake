# crankcheck_add_grade_test: the grade of your own program as one ctest test (docs/grade.md).
#
#   crankcheck_add_grade_test(NAME my_engine_grade
#                             COMMAND my_engine_program --json      # your program and its arguments
#                             [SCENES a.toml b.toml]                # default: crankcheck's built-in campaign
#                             [QUICK] [BATCH] [TIMEOUT seconds] [JOBS n] [LABELS l...])
#
# The test runs `crankcheck grade [SCENES] [--quick] [--batch] [--timeout S] [--jobs N] --out
# <current binary dir>/NAME-report -- COMMAND...` and passes when every value the program provides agrees with
# both engines (exit status 0). COMMAND may name an executable target of your project. Labels: `grade` by default.
# Installed with the package (find_package(crankcheck) defines it) and defined in crankcheck's own build.
# The folder of this file: the WILL_FAIL wrapper lives beside it (here and in an install).
set(_crankcheck_grade_cmake_dir "${CMAKE_CURRENT_LIST_DIR}")

function(crankcheck_add_grade_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "QUICK;BATCH" "NAME;TIMEOUT;JOBS" "COMMAND;SCENES;LABELS")
  if(NOT arg_NAME OR NOT arg_COMMAND)
    message(FATAL_ERROR "crankcheck_add_grade_test: NAME and COMMAND are required")
  endif()
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "crankcheck_add_grade_test: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET crankcheck::crankcheck)
    message(FATAL_ERROR "crankcheck_add_grade_test: the crankcheck program (crankcheck::crankcheck) is not available")
  endif()
  set(flags)
  if(arg_QUICK)
    list(APPEND flags --quick)
  endif()
  if(arg_BATCH)
    list(APPEND flags --batch)
  endif()
  if(arg_TIMEOUT)
    list(APPEND flags --timeout ${arg_TIMEOUT})
  endif()
  if(arg_JOBS)
    list(APPEND flags --jobs ${arg_JOBS})
  endif()
  set(program ${arg_COMMAND})
  list(POP_FRONT program first)
  if(TARGET ${first})
    set(first $<TARGET_FILE:${first}>)
  endif()
  add_test(NAME ${arg_NAME}
           COMMAND $<TARGET_FILE:crankcheck::crankcheck> grade ${arg_SCENES} ${flags}
                   --out ${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}-report -- ${first} ${program})
  if(NOT arg_LABELS)
    set(arg_LABELS grade)
  endif()
  set_tests_properties(${arg_NAME} PROPERTIES LABELS "${arg_LABELS}")
endfunction()

# crankcheck_add_free_run_grade_test: the grade of your own simulator's time-stepped runs as one ctest test
# (docs/grade.md, "Time-stepped runs").
#
#   crankcheck_add_free_run_grade_test(NAME my_simulator_runs
#                                      COMMAND my_simulator --protocol2     # your program and its arguments
#                                      SCENES a.toml [b.toml ...]         # scenes with [flywheel] for a free run
#                                      [DRIVE free|held] [DT seconds|own] [DT_SWEEP n] [REVOLUTIONS n]
#                                      [OUTPUT_INTERVAL seconds] [ENERGY_TOLERANCE x] [DELTA_TOLERANCE x]
#                                      [EXTREME_PHASE_TOLERANCE deg] [PHASE_TOLERANCE rad] [VALUES_TOLERANCE x]
#                                      [TIMEOUT seconds] [QUICK] [WILL_FAIL] [LABELS l...])
#
# QUICK: the engines' reference runs at their default accuracy or step only (seconds less per scene).
# The test runs `crankcheck grade --free-run SCENES [flags] --out <current binary dir>/NAME-report -- COMMAND...` and
# passes when every measure of the asked step is within its tolerance (exit status 0); WILL_FAIL: when some are not
# (exit status 1: a run graded and found wrong, the way a test holds that a bad step is caught). A broken run, a
# program that cannot be run or bad flags (exit status 2 or 3) fail the test either way. Labels: `grade` by default.
function(crankcheck_add_free_run_grade_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "WILL_FAIL;QUICK"
    "NAME;DRIVE;DT;DT_SWEEP;REVOLUTIONS;OUTPUT_INTERVAL;ENERGY_TOLERANCE;DELTA_TOLERANCE;EXTREME_PHASE_TOLERANCE;PHASE_TOLERANCE;VALUES_TOLERANCE;TIMEOUT"
    "COMMAND;SCENES;LABELS")
  if(NOT arg_NAME OR NOT arg_COMMAND OR NOT arg_SCENES)
    message(FATAL_ERROR "crankcheck_add_free_run_grade_test: NAME, COMMAND and SCENES are required")
  endif()
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "crankcheck_add_free_run_grade_test: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET crankcheck::crankcheck)
    message(FATAL_ERROR "crankcheck_add_free_run_grade_test: the crankcheck program (crankcheck::crankcheck) is not available")
  endif()
  set(flags)
  foreach(option DRIVE DT DT_SWEEP REVOLUTIONS OUTPUT_INTERVAL ENERGY_TOLERANCE DELTA_TOLERANCE EXTREME_PHASE_TOLERANCE
                 PHASE_TOLERANCE VALUES_TOLERANCE TIMEOUT)
    if(DEFINED arg_${option})
      string(TOLOWER "${option}" flag)
      string(REPLACE "_" "-" flag "${flag}")
      list(APPEND flags --${flag} ${arg_${option}})
    endif()
  endforeach()
  if(arg_QUICK)
    list(APPEND flags --quick)
  endif()
  set(program ${arg_COMMAND})
  list(POP_FRONT program first)
  if(TARGET ${first})
    set(first $<TARGET_FILE:${first}>)
  endif()
  if(arg_WILL_FAIL)
    # Exit status 1 (graded, out of tolerance) passes; 0, 2 and 3 fail: a wrapper keeps a broken run from passing.
    add_test(NAME ${arg_NAME}
             COMMAND ${CMAKE_COMMAND} -DCRANKCHECK=$<TARGET_FILE:crankcheck::crankcheck>
                     "-DARGS=grade;--free-run;${arg_SCENES};${flags};--out;${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}-report;--;${first};${program}"
                     -P ${_crankcheck_grade_cmake_dir}/crankcheckExpectStatus1.cmake)
  else()
    add_test(NAME ${arg_NAME}
             COMMAND $<TARGET_FILE:crankcheck::crankcheck> grade --free-run ${arg_SCENES} ${flags}
                     --out ${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}-report -- ${first} ${program})
  endif()
  if(NOT arg_LABELS)
    set(arg_LABELS grade)
  endif()
  set_tests_properties(${arg_NAME} PROPERTIES LABELS "${arg_LABELS}")
endfunction()
