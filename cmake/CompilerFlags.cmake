# Build type and warnings of crankcheck's own targets. Nothing here writes a cache variable: a project that adds
# crankcheck with add_subdirectory keeps its own flags.
#
# Release is the default build type when crankcheck is the top-level project (a normal variable, so that
# -DCMAKE_BUILD_TYPE=... on the command line still wins). CMake's Release flags contain -DNDEBUG; the rule that
# Simbody translation units never see NDEBUG (Debian's libSimTK* were built without it, SimTK::State changes
# layout under it: simbody_models/README.md) is a property of the one target that includes Simbody headers,
# crankcheck_simbody_models (simbody_models/CMakeLists.txt: -UNDEBUG after the configuration's flags; its sources
# #error if NDEBUG is defined, so the rule cannot be broken silently).
if(PROJECT_IS_TOP_LEVEL AND NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release)
endif()

# Directory-scoped (crankcheck's subdirectories only).
add_compile_options(-Wall -Wextra -Wpedantic)

# AddressSanitizer and UndefinedBehaviorSanitizer for every target of crankcheck (scripts/sanitize.sh,
# build-asan/). Simbody's own libraries are not instrumented; our code and the Simbody templates it instantiates are.
option(CRANKCHECK_SANITIZE "Build crankcheck with -fsanitize=address,undefined" OFF)
if(CRANKCHECK_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
