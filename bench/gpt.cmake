# Included from bench/CMakeLists.txt: G-PT vs PT overhead and equal-time relMSE (issue 5).
add_executable(bench_gpt ${CMAKE_CURRENT_LIST_DIR}/bench_gpt.cpp)
target_link_libraries(bench_gpt PRIVATE deltapath_integrators deltapath_manifold deltapath_scene_loaders deltapath_core)
