# Build type and flags for every target of the project.
#
# CMake's Release flags contain -DNDEBUG. A translation unit that includes Simbody headers must never see
# NDEBUG (Debian's libSimTK* were built without it; SimTK::State changes layout and realizeTopology()
# crashes). We therefore set the per-configuration flags ourselves.
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()
set(CMAKE_CXX_FLAGS_RELEASE "-O2" CACHE STRING "Release flags (no NDEBUG, see SIMBODY-NOTES.md)" FORCE)
set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O2 -g" CACHE STRING "RelWithDebInfo flags (no NDEBUG)" FORCE)
set(CMAKE_CXX_FLAGS_DEBUG "-O0 -g" CACHE STRING "Debug flags" FORCE)

add_compile_options(-Wall -Wextra -Wpedantic)

# AddressSanitizer and UndefinedBehaviorSanitizer for every target (scripts/sanitize.sh, build-asan/). Still no
# NDEBUG. Simbody's own libraries are not instrumented; our code and the Simbody templates it instantiates are.
option(CRANKCHECK_SANITIZE "Build with -fsanitize=address,undefined" OFF)
if(CRANKCHECK_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
