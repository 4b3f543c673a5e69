# Included from bench/CMakeLists.txt: solver wall times at 1280x720 (issue 4).
add_executable(bench_reconstruct ${CMAKE_CURRENT_LIST_DIR}/bench_reconstruct.cpp)
target_link_libraries(bench_reconstruct PRIVATE deltapath_reconstruct)
