# YAML scene loader and mesh readers (included by tests/scene/CMakeLists.txt).
dp_add_test(test_loader
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_yaml_loader.cpp ${CMAKE_CURRENT_LIST_DIR}/test_mesh_io.cpp
  DEPS deltapath_scene
  LABELS unit)
