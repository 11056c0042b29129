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
