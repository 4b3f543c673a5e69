# All dependencies come from Debian 12 packages (scripts/install_deps.sh); nothing is
# vendored or downloaded at build time.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Boost 1.74 REQUIRED)
find_package(OpenEXR 3 REQUIRED)
find_package(embree 3 REQUIRED)
find_package(TBB REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(tinyobjloader REQUIRED)
find_package(ZLIB REQUIRED)
# libpugixml-dev ships a CMake package (pugixml::pugixml) as well as pugixml.pc.
find_package(pugixml 1.13 CONFIG REQUIRED)
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(FFTW3F REQUIRED IMPORTED_TARGET fftw3f)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
if(DP_BUILD_TESTS)
  find_package(Catch2 2 REQUIRED)
endif()
# Optional: Open MPI for `render --mpi` (issue 17); without it the flag says so.
find_package(MPI COMPONENTS CXX QUIET)
