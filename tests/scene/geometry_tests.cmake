# Shapes, emitters and camera (scene/shapes, scene/emitters, scene/camera.*): unit tests and chi-square /
# Monte Carlo statistical tests.
dp_add_test(test_geometry
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_emitters.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_irradiance.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_shapes.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_camera.cpp
  DEPS deltapath_scene_loaders dp_test_support
  LABELS unit stat)
