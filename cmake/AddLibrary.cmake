# crankcheck_add_library(NAME STANDARD SOURCE...): the library crankcheck_NAME of the calling folder, its headers in
# the folder's include/ (installed under the include dir), C++ STANDARD (17, 20) for its users too, exported as NAME
# and aliased crankcheck::NAME. Its links and private settings stay in the folder's CMakeLists.txt.
function(crankcheck_add_library name standard)
  add_library(crankcheck_${name} ${ARGN})
  target_include_directories(crankcheck_${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                                $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(crankcheck_${name} PUBLIC cxx_std_${standard})
  set_target_properties(crankcheck_${name} PROPERTIES EXPORT_NAME ${name})
  add_library(crankcheck::${name} ALIAS crankcheck_${name})
endfunction()
