# crankcheck_add_grade_test and crankcheck_add_free_run_grade_test (cmake/crankcheckGrade.cmake) pass every argument
# exactly as written (issue 58): one holding `;`, an empty one, spaces, `$`, quotes, backslashes, brackets. Run by
# ctest as
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -P check_grade_arguments.cmake
# It writes a project in WORK_DIR (LANGUAGES NONE) whose crankcheck::crankcheck is a fake: a shell script that writes
# its argv, one argument a line as `arg:[...]` (an empty one shows as `arg:[]`), to $CRANKCHECK_FAKE_LOG and exits with
# $CRANKCHECK_FAKE_STATUS. The project includes cmake/crankcheckGrade.cmake, calls both functions (and WILL_FAIL) with
# hostile arguments, and its ctest is run; each test's log must be the argv the function promises, exactly: grade,
# the scenes, the flags, --out, --, the program (an executable target's file) and its arguments as written.
# WILL_FAIL: the fake exiting 1 passes; exiting 0, 2 or 3 fails (those tests carry ctest's WILL_FAIL, so the whole
# ctest passes only when each did what it should). Seconds: nothing is built, the fake does nothing else.
cmake_minimum_required(VERSION 3.25)
foreach(v SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "check_grade_arguments.cmake: -D${v}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")   # the test's own folder in the build tree
set(project_dir "${WORK_DIR}/project")
set(build_dir "${WORK_DIR}/build dir")   # a space in --out's folder too
set(log_dir "${WORK_DIR}/logs")
file(MAKE_DIRECTORY "${project_dir}" "${log_dir}")

# The fake crankcheck.
file(WRITE "${WORK_DIR}/fake_crankcheck.sh" [=[#!/bin/sh
: > "$CRANKCHECK_FAKE_LOG"
for a in "$@"; do
  printf 'arg:[%s]\n' "$a" >> "$CRANKCHECK_FAKE_LOG"
done
exit "$CRANKCHECK_FAKE_STATUS"
]=])
file(CHMOD "${WORK_DIR}/fake_crankcheck.sh" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE)
# The graded program: an imported executable target (COMMAND's first word becomes its file); never run by the fake.
set(program_file "${WORK_DIR}/my program")

# The arguments, each exactly (a CMake list cannot hold them): arg_<i>, i = 1..arg_count. Written into the project
# as quoted arguments, escaped (a carriage return as \r: CMake reads a raw one before a line feed as the line break).
set(arg_count 0)
function(hostile value)   # a function: a macro would evaluate its argument again
  math(EXPR n "${arg_count} + 1")
  set(arg_count ${n} PARENT_SCOPE)
  set(arg_${n} "${value}" PARENT_SCOPE)
endfunction()
hostile([==[a;b]==])
hostile("")
hostile([==[--x]==])
hostile([==[two words]==])
hostile([==[$HOME]==])
hostile([==[${not_a_variable}]==])
hostile([==[cost: $5 $$]==])
hostile([==[say "hi"]==])
hostile([==['single']==])
hostile([==[back\slash]==])
hostile([==[trailing\]==])
hostile([==[;]==])
hostile([==[;;]==])
hostile("")
hostile([==[[a]==])
hostile([==[b]]==])
hostile([==[]=]]==])
hostile([==[x]=]==])
hostile([==[#not a comment]==])
hostile([==[-DFOO=1]==])
hostile([==[-P]==])
hostile([==[--]==])
hostile([==[QUICK_NOT]==])
hostile("line one\nline two")
hostile("\nafter a newline")
hostile("a carriage\rreturn")
hostile("")

function(quoted out value)   # `value` as a CMake quoted argument
  string(REPLACE "\\" "\\\\" value "${value}")
  string(REPLACE "\"" "\\\"" value "${value}")
  string(REPLACE "$" "\\$" value "${value}")
  string(REPLACE "\r" "\\r" value "${value}")
  string(REPLACE "\n" "\\n" value "${value}")
  set(${out} "\"${value}\"" PARENT_SCOPE)
endfunction()
set(program_arguments "")   # the project's text of them
set(expected_program "")    # the log lines they must become
foreach(i RANGE 1 ${arg_count})
  quoted(q "${arg_${i}}")
  string(APPEND program_arguments " ${q}")
  string(APPEND expected_program "arg:[${arg_${i}}]\n")
endforeach()
# The scenes: paths holding `;` and a space.
set(scene_1 "${WORK_DIR}/scenes/one;two.toml")
set(scene_2 "${WORK_DIR}/scenes/with space.toml")
set(scenes "[====[${scene_1}]====] [====[${scene_2}]====]")
set(expected_scenes "arg:[${scene_1}]\narg:[${scene_2}]\n")

# Each test: its fake's status, its log, its expected argv.
file(WRITE "${project_dir}/CMakeLists.txt" "cmake_minimum_required(VERSION 3.25)
project(grade_arguments LANGUAGES NONE)
enable_testing()
add_executable(crankcheck::crankcheck IMPORTED)
set_target_properties(crankcheck::crankcheck PROPERTIES IMPORTED_LOCATION [====[${WORK_DIR}/fake_crankcheck.sh]====])
add_executable(my_program IMPORTED)
set_target_properties(my_program PROPERTIES IMPORTED_LOCATION [====[${program_file}]====])
include([====[${SOURCE_DIR}/cmake/crankcheckGrade.cmake]====])
function(fake test status)
  set_tests_properties(\${test} PROPERTIES ENVIRONMENT
                       \"CRANKCHECK_FAKE_LOG=${log_dir}/\${test}.log;CRANKCHECK_FAKE_STATUS=\${status}\")
endfunction()

crankcheck_add_grade_test(NAME grade COMMAND my_program ${program_arguments}
                          SCENES ${scenes} QUICK BATCH TIMEOUT [====[7]====] JOBS 2 LABELS a b)
fake(grade 0)
# A program named by its path, a generator expression among its arguments (evaluated, as add_test does).
crankcheck_add_grade_test(NAME grade_path COMMAND [====[${program_file}]====] [====[a;b]====] \"\"
                          [====[\$<TARGET_FILE:my_program>]====] \"\")
fake(grade_path 0)
# TIMEOUT 0 and JOBS 0 (values CMake reads as false) reach crankcheck, which refuses them; they were dropped.
crankcheck_add_grade_test(NAME grade_zero COMMAND my_program SCENES ${scenes} TIMEOUT 0 JOBS 0)
fake(grade_zero 0)
crankcheck_add_free_run_grade_test(NAME free_run COMMAND my_program ${program_arguments} SCENES ${scenes}
                                   DRIVE held DT [====[own]====] REVOLUTIONS 3 VALUES_TOLERANCE [====[0.01; x]====]
                                   QUICK)
fake(free_run 0)
crankcheck_add_free_run_grade_test(NAME will_fail COMMAND my_program ${program_arguments} SCENES ${scenes}
                                   DT 1.7e-3 WILL_FAIL TIMEOUT 5)
fake(will_fail 1)
foreach(status 0 2 3)
  crankcheck_add_free_run_grade_test(NAME will_fail_status_\${status} COMMAND my_program ${program_arguments}
                                     SCENES ${scenes} WILL_FAIL)
  fake(will_fail_status_\${status} \${status})
  set_tests_properties(will_fail_status_\${status} PROPERTIES WILL_FAIL TRUE)   # the wrapper must fail
endforeach()
")

set(out "arg:[--out]\narg:[${build_dir}/")
set(rest "-report]\narg:[--]\narg:[${program_file}]\n${expected_program}")
set(expected_grade "arg:[grade]\n${expected_scenes}arg:[--quick]\narg:[--batch]\narg:[--timeout]\narg:[7]\n")
string(APPEND expected_grade "arg:[--jobs]\narg:[2]\n${out}grade${rest}")
set(expected_grade_path "arg:[grade]\n${out}grade_path-report]\narg:[--]\narg:[${program_file}]\narg:[a;b]\narg:[]\n")
string(APPEND expected_grade_path "arg:[${program_file}]\narg:[]\n")
set(expected_free_run "arg:[grade]\narg:[--free-run]\n${expected_scenes}arg:[--drive]\narg:[held]\narg:[--dt]\n")
string(APPEND expected_free_run "arg:[own]\narg:[--revolutions]\narg:[3]\narg:[--values-tolerance]\narg:[0.01; x]\n")
string(APPEND expected_free_run "arg:[--quick]\n${out}free_run${rest}")
set(expected_will_fail "arg:[grade]\narg:[--free-run]\n${expected_scenes}arg:[--dt]\narg:[1.7e-3]\narg:[--timeout]\n")
string(APPEND expected_will_fail "arg:[5]\n${out}will_fail${rest}")
set(expected_grade_zero "arg:[grade]\n${expected_scenes}arg:[--timeout]\narg:[0]\narg:[--jobs]\narg:[0]\n")
string(APPEND expected_grade_zero "${out}grade_zero-report]\narg:[--]\narg:[${program_file}]\n")
set(tests grade grade_path grade_zero free_run will_fail)
foreach(status 0 2 3)
  set(expected_will_fail_status_${status} "arg:[grade]\narg:[--free-run]\n${expected_scenes}")
  string(APPEND expected_will_fail_status_${status} "${out}will_fail_status_${status}${rest}")
  list(APPEND tests will_fail_status_${status})
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ok")
endfunction()
run("configure" ${CMAKE_COMMAND} -S "${project_dir}" -B "${build_dir}")
run("ctest" ${CMAKE_CTEST_COMMAND} --test-dir "${build_dir}" --output-on-failure)

# first_difference(out got expected): "line N: `got's line` instead of `expected's line`", the first line that differs.
function(first_difference out got expected)
  set(n 1)
  while(NOT got STREQUAL expected)
    foreach(text got expected)
      string(FIND "${${text}}" "\n" at)
      if(at EQUAL -1)
        set(${text}_line "${${text}}")
        set(${text} "")
      else()
        string(SUBSTRING "${${text}}" 0 ${at} ${text}_line)
        math(EXPR at "${at} + 1")
        string(SUBSTRING "${${text}}" ${at} -1 ${text})
      endif()
    endforeach()
    if(NOT got_line STREQUAL expected_line)
      set(${out} "line ${n}: `${got_line}` instead of `${expected_line}`" PARENT_SCOPE)
      return()
    endif()
    math(EXPR n "${n} + 1")
  endwhile()
endfunction()
set(wrong "")
set(summary "")
foreach(test IN LISTS tests)
  set(log "${log_dir}/${test}.log")
  if(NOT EXISTS "${log}")
    string(APPEND wrong "\n${test}: the fake crankcheck was not run")
    continue()
  endif()
  file(READ "${log}" got)
  if(NOT got STREQUAL expected_${test})
    string(APPEND wrong "\n${test}: the fake crankcheck received\n${got}instead of\n${expected_${test}}")
    first_difference(difference "${got}" "${expected_${test}}")
    string(APPEND summary "\n  ${test}: ${difference}")
  endif()
endforeach()
if(wrong)
  file(READ "${build_dir}/CTestTestfile.cmake" testfile)
  message(NOTICE "${wrong}\nCTestTestfile.cmake:\n${testfile}")   # as it is (FATAL_ERROR reflows its text)
  message(NOTICE "arguments not passed exactly (the whole argv above), first differences:${summary}")
  message(FATAL_ERROR "arguments not passed exactly")
endif()
list(LENGTH tests count)
message(STATUS "${count} tests: every argument reached the program exactly as written")

# expect_refused(name call pattern what): a project whose one line `call` must be refused when configured, with an
# error matching `pattern`.
function(expect_refused name call pattern what)
  file(WRITE "${WORK_DIR}/${name}/CMakeLists.txt" "cmake_minimum_required(VERSION 3.25)
project(grade_arguments_${name} LANGUAGES NONE)
enable_testing()
add_executable(crankcheck::crankcheck IMPORTED)
set_target_properties(crankcheck::crankcheck PROPERTIES IMPORTED_LOCATION [====[${WORK_DIR}/fake_crankcheck.sh]====])
include([====[${SOURCE_DIR}/cmake/crankcheckGrade.cmake]====])
${call}
")
  execute_process(COMMAND ${CMAKE_COMMAND} -S "${WORK_DIR}/${name}" -B "${WORK_DIR}/${name}-build"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "${what} was not refused (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: refused")
endfunction()

# The one argument no test can pass on, a carriage return before a line feed (CTestTestfile.cmake holds it as it is and
# ctest reads a line break), is refused when the test is added, not changed.
expect_refused(refused "crankcheck_add_free_run_grade_test(NAME refused COMMAND my_program \"line\\r\\nbreak\" SCENES a.toml WILL_FAIL)"
               "carriage return before a line feed" "a carriage return before a line feed")
# A NAME with a path separator would put its report outside the build tree (NAME-report): refused when added.
expect_refused(refused_name "crankcheck_add_grade_test(NAME ../../x COMMAND my_program)"
               "NAME ../../x: a test name without /" "a NAME with a path separator")
