# Included from bench/CMakeLists.txt: solver wall times at 1280x720 (issue 4).
add_executable(bench_reconstruct ${CMAKE_CURRENT_LIST_DIR}/bench_reconstruct.cpp)
target_link_libraries(bench_reconstruct PRIVATE deltapath_reconstruct)
# Wall time per phase of the L1 grid solve's IRLS loop (issue 18).
add_executable(bench_l1_phases ${CMAKE_CURRENT_LIST_DIR}/bench_l1_phases.cpp)
target_link_libraries(bench_l1_phases PRIVATE deltapath_reconstruct)
# Memory bandwidth (triad), the roof of the bandwidth-bound L1 grid solve (issue 18).
add_executable(bench_bandwidth ${CMAKE_CURRENT_LIST_DIR}/bench_bandwidth.cpp)
target_link_libraries(bench_bandwidth PRIVATE Threads::Threads)
