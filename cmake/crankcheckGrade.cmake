# crankcheck_add_grade_test: the grade of your own program as one ctest test (docs/grade.md).
#
#   crankcheck_add_grade_test(NAME my_engine_grade
#                             COMMAND my_engine_program --json      # your program and its arguments
#                             [SCENES a.toml b.toml]                # default: crankcheck's built-in campaign
#                             [QUICK] [BATCH] [TIMEOUT seconds] [JOBS n] [LABELS l...])
#
# The test runs `crankcheck grade [SCENES] [--quick] [--batch] [--timeout S] [--jobs N] --out
# <current binary dir>/NAME-report -- COMMAND...` and passes when every value the program provides agrees with
# every reference engine (exit status 0). COMMAND may name an executable target of your project. Labels: `grade` by default.
# Every argument (COMMAND's, SCENES, the values) reaches the program exactly as written: one holding `;` stays one
# argument and an empty one is kept (issue 58); generator expressions are evaluated as add_test evaluates them. A
# program argument spelled like one of the function's keywords (QUICK, SCENES, ...) is taken as that keyword; one
# holding a carriage return before a line feed is refused (ctest would read a line break).
# Installed with the package (find_package(crankcheck) defines it) and defined in crankcheck's own build.
cmake_policy(VERSION 3.25)   # for this file's functions (include() scopes it), whatever the including project's
# The folder of this file: the WILL_FAIL wrapper lives beside it (here and in an install).
set(_crankcheck_grade_cmake_dir "${CMAKE_CURRENT_LIST_DIR}")

# _crankcheck_quote(out value): `value` as CMake code of one bracket argument holding it exactly: its bracket's `=`s
# are a run that cannot close it early, and a value that starts with a line break gets a newline after the opening
# bracket (CMake drops that one newline) to keep its own.
function(_crankcheck_quote out value)
  set(eq "")
  while(TRUE)
    string(FIND "${value}]${eq}" "]${eq}]" at)   # a closing bracket ending before the one appended
    if(at EQUAL -1)
      break()
    endif()
    string(APPEND eq "=")
  endwhile()
  set(newline "")
  if(value MATCHES "^[\r\n]")
    set(newline "\n")
  endif()
  set(${out} "[${eq}[${newline}${value}]${eq}]" PARENT_SCOPE)
endfunction()

# _crankcheck_grade_values(${ARGC} prefix "options" "one-value keywords" "multi-value keywords"): the values of the
# calling function's keywords, each exactly. A macro, so that ${ARGV<i>} are the calling function's arguments, each
# one argument as written (cmake_parse_arguments(PARSE_ARGV) escapes only `;` in its lists, which is ambiguous beside a
# backslash or a bracket, and expanding a list loses `;` and empty elements). The same parse as
# cmake_parse_arguments: a keyword starts its values, a one-value keyword takes one (the last occurrence counts), a
# multi-value keyword's occurrences add up. For each one-value or multi-value keyword K: _crankcheck_K, its values as
# CMake code (one bracket argument each, `prefix` before each value, a space before each argument);
# _crankcheck_K_first, its first value as it is; _crankcheck_K_rest, the code of the values after the first. A value
# holding a carriage return before a line feed is refused (no test can pass it on).
macro(_crankcheck_grade_values argc prefix options one_value multi_value)
  set(_crankcheck_options "${options}")
  set(_crankcheck_one_value "${one_value}")
  set(_crankcheck_multi_value "${multi_value}")
  foreach(_crankcheck_keyword IN LISTS _crankcheck_one_value _crankcheck_multi_value)
    set(_crankcheck_${_crankcheck_keyword} "")
    set(_crankcheck_${_crankcheck_keyword}_rest "")
    unset(_crankcheck_${_crankcheck_keyword}_first)
  endforeach()
  set(_crankcheck_keyword "")
  math(EXPR _crankcheck_last "${argc} - 1")
  foreach(_crankcheck_i RANGE ${_crankcheck_last})
    set(_crankcheck_value "${ARGV${_crankcheck_i}}")
    if(_crankcheck_value IN_LIST _crankcheck_options)
      set(_crankcheck_keyword "")
    elseif(_crankcheck_value IN_LIST _crankcheck_one_value)
      set(_crankcheck_keyword "${_crankcheck_value}")
      set(_crankcheck_${_crankcheck_keyword} "")
      set(_crankcheck_${_crankcheck_keyword}_rest "")
      unset(_crankcheck_${_crankcheck_keyword}_first)
    elseif(_crankcheck_value IN_LIST _crankcheck_multi_value)
      set(_crankcheck_keyword "${_crankcheck_value}")
    elseif(NOT _crankcheck_keyword STREQUAL "")
      if(_crankcheck_value MATCHES "\r\n")
        message(FATAL_ERROR "${CMAKE_CURRENT_FUNCTION}: the argument of ${_crankcheck_keyword} '${_crankcheck_value}' "
                            "holds a carriage return before a line feed, which a test cannot pass on (CMake writes "
                            "it into CTestTestfile.cmake as it is, and ctest reads it there as a line break)")
      endif()
      _crankcheck_quote(_crankcheck_quoted "${prefix}${_crankcheck_value}")
      string(APPEND _crankcheck_${_crankcheck_keyword} " ${_crankcheck_quoted}")
      if(DEFINED _crankcheck_${_crankcheck_keyword}_first)
        string(APPEND _crankcheck_${_crankcheck_keyword}_rest " ${_crankcheck_quoted}")
      else()
        set(_crankcheck_${_crankcheck_keyword}_first "${_crankcheck_value}")
      endif()
      if(_crankcheck_keyword IN_LIST _crankcheck_one_value)
        set(_crankcheck_keyword "")   # what follows its one value is unparsed (cmake_parse_arguments refused it)
      endif()
    endif()
  endforeach()
endmacro()

# _crankcheck_grade_add_test(name code): add_test(NAME name COMMAND <code>), `code` the command's arguments as CMake
# code (bracket arguments): each reaches the program as one argument, exactly (add_test keeps a quoted `;` and an
# empty quoted argument; CTestTestfile.cmake holds them quoted).
function(_crankcheck_grade_add_test name code)
  _crankcheck_quote(name_code "${name}")
  cmake_language(EVAL CODE "add_test(NAME ${name_code} COMMAND ${code})")
endfunction()

# The test's NAME names its report folder, <current binary dir>/NAME-report: a name with a path separator (or `.`,
# `..`) would put the report elsewhere (`../../x`), so it is refused.
function(_crankcheck_check_name function name)
  if(name MATCHES "[/\\]" OR name STREQUAL "." OR name STREQUAL "..")
    message(FATAL_ERROR "${function}: NAME ${name}: a test name without / or \\ (its report is written to "
                        "${CMAKE_CURRENT_BINARY_DIR}/NAME-report)")
  endif()
endfunction()

function(crankcheck_add_grade_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "QUICK;BATCH" "NAME;TIMEOUT;JOBS" "COMMAND;SCENES;LABELS")
  if(NOT arg_NAME OR NOT arg_COMMAND)
    message(FATAL_ERROR "crankcheck_add_grade_test: NAME and COMMAND are required")
  endif()
  _crankcheck_check_name(crankcheck_add_grade_test "${arg_NAME}")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "crankcheck_add_grade_test: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET crankcheck::crankcheck)
    message(FATAL_ERROR "crankcheck_add_grade_test: the crankcheck program (crankcheck::crankcheck) is not available")
  endif()
  _crankcheck_grade_values(${ARGC} "" "QUICK;BATCH" "NAME;TIMEOUT;JOBS" "COMMAND;SCENES;LABELS")
  set(flags "")   # CMake code, like the values
  if(arg_QUICK)
    string(APPEND flags " --quick")
  endif()
  if(arg_BATCH)
    string(APPEND flags " --batch")
  endif()
  # DEFINED, not the value's truth: TIMEOUT 0 or OFF reaches crankcheck, which refuses it, rather than being dropped.
  if(DEFINED arg_TIMEOUT)
    string(APPEND flags " --timeout${_crankcheck_TIMEOUT}")
  endif()
  if(DEFINED arg_JOBS)
    string(APPEND flags " --jobs${_crankcheck_JOBS}")
  endif()
  set(first "${_crankcheck_COMMAND_first}")
  if(TARGET "${first}")
    set(first "$<TARGET_FILE:${first}>")
  endif()
  _crankcheck_quote(first "${first}")
  _crankcheck_quote(out "${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}-report")
  set(command "\"$<TARGET_FILE:crankcheck::crankcheck>\" grade${_crankcheck_SCENES}${flags}")
  string(APPEND command " --out ${out} -- ${first}${_crankcheck_COMMAND_rest}")
  _crankcheck_grade_add_test("${arg_NAME}" "${command}")
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
# COMMAND may name an executable target; every argument reaches the program exactly as written, WILL_FAIL's too (as
# for crankcheck_add_grade_test).
function(crankcheck_add_free_run_grade_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "WILL_FAIL;QUICK"
    "NAME;DRIVE;DT;DT_SWEEP;REVOLUTIONS;OUTPUT_INTERVAL;ENERGY_TOLERANCE;DELTA_TOLERANCE;EXTREME_PHASE_TOLERANCE;PHASE_TOLERANCE;VALUES_TOLERANCE;TIMEOUT"
    "COMMAND;SCENES;LABELS")
  if(NOT arg_NAME OR NOT arg_COMMAND OR NOT arg_SCENES)
    message(FATAL_ERROR "crankcheck_add_free_run_grade_test: NAME, COMMAND and SCENES are required")
  endif()
  _crankcheck_check_name(crankcheck_add_free_run_grade_test "${arg_NAME}")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "crankcheck_add_free_run_grade_test: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET crankcheck::crankcheck)
    message(FATAL_ERROR "crankcheck_add_free_run_grade_test: the crankcheck program (crankcheck::crankcheck) is not available")
  endif()
  # WILL_FAIL: exit status 1 (graded, out of tolerance) passes; 0, 2 and 3 fail: a wrapper keeps a broken run from
  # passing. It runs the command after `cmake -P crankcheckExpectStatus1.cmake --`, each argument one of the wrapper's
  # own with a `+` before it (a -D list would lose `;` and empty arguments, and cmake 3.25 still reads some arguments
  # after `--` as its options, -P among them: none starts with `+`).
  set(p "")
  if(arg_WILL_FAIL)
    set(p "+")
  endif()
  set(one_value NAME DRIVE DT DT_SWEEP REVOLUTIONS OUTPUT_INTERVAL ENERGY_TOLERANCE DELTA_TOLERANCE
                EXTREME_PHASE_TOLERANCE PHASE_TOLERANCE VALUES_TOLERANCE TIMEOUT)
  _crankcheck_grade_values(${ARGC} "${p}" "WILL_FAIL;QUICK" "${one_value}" "COMMAND;SCENES;LABELS")
  set(flags "")   # CMake code, like the values
  foreach(option DRIVE DT DT_SWEEP REVOLUTIONS OUTPUT_INTERVAL ENERGY_TOLERANCE DELTA_TOLERANCE EXTREME_PHASE_TOLERANCE
                 PHASE_TOLERANCE VALUES_TOLERANCE TIMEOUT)
    if(DEFINED arg_${option})
      string(TOLOWER "${option}" flag)
      string(REPLACE "_" "-" flag "${flag}")
      string(APPEND flags " ${p}--${flag}${_crankcheck_${option}}")
    endif()
  endforeach()
  if(arg_QUICK)
    string(APPEND flags " ${p}--quick")
  endif()
  set(first "${_crankcheck_COMMAND_first}")
  if(TARGET "${first}")
    set(first "$<TARGET_FILE:${first}>")
  endif()
  _crankcheck_quote(first "${p}${first}")
  _crankcheck_quote(out "${p}${CMAKE_CURRENT_BINARY_DIR}/${arg_NAME}-report")
  set(command "\"${p}$<TARGET_FILE:crankcheck::crankcheck>\" ${p}grade ${p}--free-run${_crankcheck_SCENES}${flags}")
  string(APPEND command " ${p}--out ${out} ${p}-- ${first}${_crankcheck_COMMAND_rest}")
  if(arg_WILL_FAIL)
    _crankcheck_quote(cmake "${CMAKE_COMMAND}")
    _crankcheck_quote(wrapper "${_crankcheck_grade_cmake_dir}/crankcheckExpectStatus1.cmake")
    set(command "${cmake} -P ${wrapper} -- ${command}")
  endif()
  _crankcheck_grade_add_test("${arg_NAME}" "${command}")
  if(NOT arg_LABELS)
    set(arg_LABELS grade)
  endif()
  set_tests_properties(${arg_NAME} PROPERTIES LABELS "${arg_LABELS}")
endfunction()
