# YAML scene loader, mesh readers and extreme inputs to both front ends (issue 18)
# (included by tests/scene/CMakeLists.txt).
dp_add_test(test_loader
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_yaml_loader.cpp ${CMAKE_CURRENT_LIST_DIR}/test_mesh_io.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_extreme_inputs.cpp
  DEPS deltapath_scene_loaders
  LABELS unit)
