# Included from bench/CMakeLists.txt: manifold-walk cost and success rates (issue 6).
add_executable(bench_manifold ${CMAKE_CURRENT_LIST_DIR}/bench_manifold.cpp)
target_link_libraries(bench_manifold PRIVATE deltapath_manifold)
