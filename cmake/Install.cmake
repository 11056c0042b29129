# `cmake --install build --prefix P`: the libraries and their headers, the crankcheck CLI, the gnuplot scripts of
# the report, the example scenes, and the CMake package (P/lib/cmake/crankcheck/crankcheckConfig.cmake) with its targets:
#   crankcheck::scene, crankcheck::analytic                     (need toml++ and Eigen)
#   crankcheck::simbody_models, crankcheck::validation,
#   crankcheck::crankcheck (the CLI, an imported executable)    (need Simbody, Google Benchmark, nlohmann-json)
# Two export sets, so that a consumer of the analytic library does not need Simbody installed.
include(CMakePackageConfigHelpers)

set(CRANKCHECK_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/crankcheck)

install(TARGETS crankcheck_scene crankcheck_analytic EXPORT crankcheckCoreTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS crankcheck_simbody_models crankcheck_validation crankcheck EXPORT crankcheckSimbodyTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(part scene analytic simbody_models validation)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${part}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/reports/ DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/reports
        FILES_MATCHING PATTERN "*.gp" PATTERN "*.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${CRANKCHECK_DATA_INSTALL_DIR}/scenes
        FILES_MATCHING PATTERN "*.toml")

install(EXPORT crankcheckCoreTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
install(EXPORT crankcheckSimbodyTargets NAMESPACE crankcheck:: DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/crankcheckConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/crankcheckConfig.cmake
                              INSTALL_DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/crankcheckConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/crankcheckConfig.cmake ${PROJECT_BINARY_DIR}/crankcheckConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/crankcheckGrade.cmake
        DESTINATION ${CRANKCHECK_CMAKE_INSTALL_DIR})
