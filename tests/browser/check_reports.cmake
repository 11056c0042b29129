# The reports as a reader opens them (issue 11, label `browser`): a quick validate report and a quick grade report,
# each opened in headless Chromium by check_report.py (console errors, images that did not load, lang, title,
# table of contents; the screenshots stay in WORK_DIR). Run by ctest as
#   cmake -DCRANKCHECK=... -DGRADE_PROGRAM=... -DCHROMIUM=... -DPYTHON=... -DWORK_DIR=... [-DVALIDATE_REPORT=...]
#         -P check_reports.cmake
# VALIDATE_REPORT: the quick validate report to open, already written (under ctest the fixture quick_campaign's,
# shared with the CLI tests that read it, issue 28); without it the script runs `validate --quick` itself.
cmake_minimum_required(VERSION 3.25)
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ${out}")
endfunction()
file(REMOVE_RECURSE ${WORK_DIR})  # the test's own folder in the build tree
file(MAKE_DIRECTORY ${WORK_DIR})
if(NOT VALIDATE_REPORT)
  set(VALIDATE_REPORT ${WORK_DIR}/validate)
  run("validate --quick" ${CRANKCHECK} validate --quick --out ${VALIDATE_REPORT})
endif()
if(NOT EXISTS ${VALIDATE_REPORT}/index.html)
  message(FATAL_ERROR "${VALIDATE_REPORT}: no index.html (the quick campaign's report)")
endif()
# The anchors: the report's sections and a part's key (#torsion in every report), not positions (#part20).
run("validate report in Chromium" ${PYTHON} ${CMAKE_CURRENT_LIST_DIR}/check_report.py ${CHROMIUM} ${VALIDATE_REPORT}
    ${WORK_DIR}/validate_report.png --verdict-first --anchors verdict,summary,scenes,error_vs_lambda,torsion)
# A user's report (USER_REPORT: the quick campaign of one example scene as a user gives it): the scene's own section
# ("NAME: your engine") begins within the first two screens, right after the verdict.
if(USER_REPORT)
  if(NOT EXISTS ${USER_REPORT}/index.html)
    message(FATAL_ERROR "${USER_REPORT}: no index.html (the one-scene campaign's report)")
  endif()
  run("user report in Chromium" ${PYTHON} ${CMAKE_CURRENT_LIST_DIR}/check_report.py ${CHROMIUM} ${USER_REPORT}
      ${WORK_DIR}/user_report.png --verdict-first --near-top your-engine-${USER_SCENE}
      --section-shot your-engine-${USER_SCENE} ${WORK_DIR}/user_scene_section.png)
endif()
run("grade --quick" ${CRANKCHECK} grade --quick --batch --out ${WORK_DIR}/grade -- ${GRADE_PROGRAM})
run("grade report in Chromium" ${PYTHON} ${CMAKE_CURRENT_LIST_DIR}/check_report.py ${CHROMIUM} ${WORK_DIR}/grade
    ${WORK_DIR}/grade_report.png)
