# The CMake package as a user meets it (issue 11): run by ctest as
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DVERSION=... -P check_install.cmake
# 1. `cmake --install BUILD_DIR --prefix WORK_DIR/prefix`;
# 2. examples/consumer configured against that prefix (find_package(crankcheck 0.2)), built, both programs run;
# 3. the same with COMPONENTS analytic while Simbody cannot be found (the analytic library needs no Simbody), and
#    while MuJoCo cannot be found;
# 4. the installed CLI: its --version is the project's, and `validate --quick --parts ...` draws the figures with the gnuplot
#    scripts it finds relative to itself (the build's install prefix is not WORK_DIR/prefix, so no compiled-in
#    path can be what found them);
# 5. examples/consumer configured with add_subdirectory(SOURCE_DIR) (ALIAS targets, no tests of crankcheck's own);
# Also: the man pages, the docs (every link resolving within the install) and the scenes' schema.
# 6. examples/grade_gate, a project with LANGUAGES NONE that only runs the grade gate, configured with every library
#    dependency hidden (toml++, Eigen, Simbody, MuJoCo, Google Benchmark, nlohmann-json) and its ctest run on
#    GRADE_PROGRAM; crankcheck_EXECUTABLE is the installed program.
# Every step stops the test with the step's output on failure. Commands are run without a shell.
cmake_minimum_required(VERSION 3.25)
foreach(v BUILD_DIR SOURCE_DIR WORK_DIR VERSION GRADE_PROGRAM PYTHON)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "check_install.cmake: -D${v}=... is required")
  endif()
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
  message(STATUS "${what}: ok")
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})   # the test's own folder in the build tree
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(consumer ${SOURCE_DIR}/examples/consumer)

run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f lib/cmake/crankcheck/crankcheckConfig.cmake lib/cmake/crankcheck/crankcheckConfigVersion.cmake
          include/crankcheck/analytic/gravity_torque.h bin/crankcheck share/crankcheck/reports/error_vs_lambda.gp
          share/crankcheck/scenes/single_cylinder.toml share/crankcheck/README.md
          share/crankcheck/docs/SCENE-FORMAT.md share/crankcheck/docs/scene.schema.json)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "install: ${prefix}/${f} is missing")
  endif()
endforeach()
# The man pages, one per command, from --help: each names its command in its synopsis.
foreach(command "" eval motion flywheel balance torsion validate grade "report merge")
  set(page crankcheck)
  if(command)
    string(REPLACE " " "-" dashed "${command}")
    set(page crankcheck-${dashed})
  endif()
  set(man ${prefix}/share/man/man1/${page}.1)
  if(NOT EXISTS ${man})
    message(FATAL_ERROR "install: ${man} is missing")
  endif()
  file(READ ${man} text)
  string(STRIP "crankcheck ${command}" usage)
  if(NOT text MATCHES ".SH SYNOPSIS\n.nf\n${usage} \\[OPTIONS\\]")
    message(FATAL_ERROR "install: ${man} has no synopsis of '${usage}':\n${text}")
  endif()
endforeach()
# Every link of the installed docs resolves in the install (the checker reads every file of a folder git does not
# track: the install's share/crankcheck).
run("installed docs: links" ${PYTHON} ${SOURCE_DIR}/tests/meta/check_links.py ${prefix}/share/crankcheck)
# Every installed scene's `#:schema` names a file of the install.
file(GLOB installed_scenes ${prefix}/share/crankcheck/scenes/*.toml)
foreach(scene ${installed_scenes})
  file(STRINGS ${scene} schema_lines REGEX "^#:schema ")
  foreach(line ${schema_lines})
    string(REGEX REPLACE "^#:schema " "" schema "${line}")
    get_filename_component(dir ${scene} DIRECTORY)
    if(NOT EXISTS ${dir}/${schema})
      message(FATAL_ERROR "install: ${scene} names the schema ${schema}, which the install does not hold")
    endif()
  endforeach()
endforeach()

run("consumer: configure" ${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/consumer -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
run("consumer: build" ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer -j2)
run("consumer: gravity_torque_check" ${WORK_DIR}/consumer/gravity_torque_check)
run("consumer: engines_agree" ${WORK_DIR}/consumer/engines_agree)

run("analytic-only consumer: configure without Simbody" ${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/analytic_only
    -DCMAKE_PREFIX_PATH=${prefix} -DANALYTIC_ONLY=ON -DCMAKE_DISABLE_FIND_PACKAGE_Simbody=ON
    -DCMAKE_BUILD_TYPE=Release)
run("analytic-only consumer: build" ${CMAKE_COMMAND} --build ${WORK_DIR}/analytic_only -j2)
run("analytic-only consumer: run" ${WORK_DIR}/analytic_only/gravity_torque_check)
# A consumer that does not want MuJoCo: the same with MuJoCo's package hidden.
run("consumer without MuJoCo: configure" ${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/without_mujoco
    -DCMAKE_PREFIX_PATH=${prefix} -DANALYTIC_ONLY=ON -DCMAKE_DISABLE_FIND_PACKAGE_mujoco=ON -DCMAKE_BUILD_TYPE=Release)
run("consumer without MuJoCo: build" ${CMAKE_COMMAND} --build ${WORK_DIR}/without_mujoco -j2)

run("installed CLI: --version" ${prefix}/bin/crankcheck --version)
if(NOT run_output MATCHES "crankcheck ${VERSION}")
  message(FATAL_ERROR "installed CLI: --version printed '${run_output}', expected crankcheck ${VERSION}")
endif()
# Two parts: one on the built-in scenes, one on the example scenes the CLI finds beside itself (share/crankcheck/).
run("installed CLI: validate --quick" ${CMAKE_COMMAND} -E env --unset=CRANKCHECK_REPORTS_DIR --unset=CRANKCHECK_SCENES_DIR
    ${prefix}/bin/crankcheck validate --quick --parts error_vs_lambda,pin_load_polar --out ${WORK_DIR}/report)
if(NOT EXISTS ${WORK_DIR}/report/error_vs_lambda.png OR NOT EXISTS ${WORK_DIR}/report/pin_load_polar.png)
  message(FATAL_ERROR "installed CLI: the report lacks its figures")
endif()

run("add_subdirectory consumer: configure" ${CMAKE_COMMAND} -S ${consumer} -B ${WORK_DIR}/from_source
    -DCRANKCHECK_SOURCE_DIR=${SOURCE_DIR})
if(EXISTS ${WORK_DIR}/from_source/crankcheck/tests)
  message(FATAL_ERROR "add_subdirectory consumer: crankcheck's own tests were configured in a consumer's build")
endif()

run("grade gate (LANGUAGES NONE, no library dependency): configure" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/grade_gate
    -B ${WORK_DIR}/grade_gate -DCMAKE_PREFIX_PATH=${prefix} -DGRADED_PROGRAM=${GRADE_PROGRAM}
    -DFREE_RUN_PROGRAM=${prefix}/share/crankcheck/examples/free_run/rk4_reduced.py
    -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_Simbody=ON -DCMAKE_DISABLE_FIND_PACKAGE_mujoco=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON)
if(NOT run_output MATCHES "crankcheck: ${prefix}/bin/crankcheck")
  message(FATAL_ERROR "grade gate: crankcheck_EXECUTABLE is not ${prefix}/bin/crankcheck:\n${run_output}")
endif()
run("grade gate: ctest" ${CMAKE_CTEST_COMMAND} --test-dir ${WORK_DIR}/grade_gate --output-on-failure)
if(NOT run_output MATCHES "100% tests passed, 0 tests failed out of 2")
  message(FATAL_ERROR "grade gate: ctest ran no grade, or not the free run's:\n${run_output}")
endif()
