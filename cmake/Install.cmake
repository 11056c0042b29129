# `cmake --install build --prefix P`: the libraries and their headers, the crankcheck CLI and its man pages, the
# gnuplot scripts of the report, the example scenes, the docs, and the CMake package (P/lib/cmake/crankcheck/crankcheckConfig.cmake) with its targets:
#   crankcheck::scene, crankcheck::solver, crankcheck::analytic (need toml++ and Eigen)
#   crankcheck::simbody_models                                  (needs Simbody)
#   crankcheck::mujoco_models                                   (needs MuJoCo, Debian libmujoco-dev)
#   crankcheck::ode_models, bullet_models, box2d_models          (the stepped engines: ODE, Bullet, Box2D, Debian
#                                                                libode-dev, libbullet-dev, libbox2d-dev)
#   crankcheck::validation                                      (needs every engine, Google Benchmark, nlohmann-json)
#   crankcheck::crankcheck (the CLI, an imported executable)    (needs nothing: a grade gate needs no compiler)
# One export set per engine, one for the harness and one for the program, so that a consumer of the analytic library
# needs neither Simbody nor MuJoCo installed, a consumer of one engine not the other, and a project that only runs
# the CLI (crankcheck_add_grade_test) none of the libraries' dependencies.
include(CMakePackageConfigHelpers)

set(CRANKCHECK_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/crankcheck)

install(TARGETS crankcheck_scene crankcheck_solver crankcheck_analytic EXPORT crankcheckCoreTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS crankcheck_simbody_models EXPORT crankcheckSimbodyTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS crankcheck_mujoco_models EXPORT crankcheckMujocoTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS crankcheck_ode_models crankcheck_bullet_models crankcheck_box2d_models EXPORT crankcheckSteppedTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS crankcheck_validation EXPORT crankcheckHarnessTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS crankcheck EXPORT crankcheckProgramTargets RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(part scene solver analytic simbody_models mujoco_models ode_models bullet_models box2d_models validation)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${part}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/reports/ DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/reports
        FILES_MATCHING PATTERN "*.gp" PATTERN "*.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/scenes
        FILES_MATCHING PATTERN "*.toml")
# The docs a user needs without the repository (scene format and schema, conventions, grade's protocol, every
# command's page) and the README they start from: PREFIX/share/crankcheck/{README.md,docs/}. The man pages are
# installed with the program (app/CMakeLists.txt).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/docs)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR})
# What the docs link to, at the same places relative to them: the examples (a consumer project, the grade gate, the
# graded programs), the measurements' log and the engines' notes (every link of the installed docs resolves:
# tests/package/check_install.cmake runs tests/meta/check_links.py on the install).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/examples
        USE_SOURCE_PERMISSIONS)  # the example programs stay executable
install(FILES ${PROJECT_SOURCE_DIR}/bench/README.md DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/bench)
foreach(engine simbody_models mujoco_models)
  install(FILES ${PROJECT_SOURCE_DIR}/${engine}/README.md DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/${engine})
endforeach()

install(EXPORT crankcheckCoreTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
install(EXPORT crankcheckSimbodyTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
install(EXPORT crankcheckMujocoTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
install(EXPORT crankcheckSteppedTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
install(EXPORT crankcheckHarnessTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
install(EXPORT crankcheckProgramTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/crankcheckConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/crankcheckConfig.cmake
                              INSTALL_DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR}
                              PATH_VARS CMAKE_INSTALL_BINDIR CRANKCHECK_DATA_INSTALL_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/crankcheckConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/crankcheckConfig.cmake ${PROJECT_BINARY_DIR}/crankcheckConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/crankcheckGrade.cmake ${PROJECT_SOURCE_DIR}/cmake/crankcheckExpectStatus1.cmake
        DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
